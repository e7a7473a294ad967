//! A procedural-modelling session with attributes: colour the faces of a
//! cube, give its vertices a mass and a selection flag, then split, poke,
//! flip, merge and collapse, and watch how each rule carries the values.
//!
//! Run with `cargo run --example attributes`.

use meshloom::attr::{Conserved, FaceAttr, VertexAttr};
use meshloom::{FaceKey, Mesh, Result, VertexKey};

/// Everything the session tracks.
struct Session {
    mesh: Mesh,
    colour: FaceAttr<[f32; 3]>,
    material: FaceAttr<u32>,
    mass: VertexAttr<f64, Conserved>,
    selected: VertexAttr<bool>,
}

impl Session {
    fn report(&self, step: &str) -> Result<()> {
        let m = &self.mesh;
        let mass: f64 = m.attr_view(&self.mass)?.iter().map(|(_, x)| x).sum();
        let weighed = m.attr_view(&self.mass)?.iter().count();
        let colours = m.attr_view(&self.colour)?;
        let mut distinct: Vec<[u32; 3]> = m
            .faces()
            .filter_map(|f| colours.get(f))
            .map(|c| c.map(|x| (x * 1000.0).round() as u32))
            .collect();
        distinct.sort_unstable();
        distinct.dedup();
        let no_material = m
            .faces()
            .filter(|&f| matches!(m.attr(&self.material, f), Ok(None)))
            .count();
        let selected = m
            .attr_view(&self.selected)?
            .iter()
            .filter(|(_, s)| **s)
            .count();
        println!(
            "{step:<44} V={:<3} F={:<3} mass={mass:<5.2} ({weighed} weighed) \
             colours={:<2} no-material={no_material} selected={selected}",
            m.vertex_count(),
            m.face_count(),
            distinct.len(),
        );
        Ok(())
    }
}

fn colour_of(s: &Session, f: FaceKey) -> Result<String> {
    Ok(match s.mesh.attr(&s.colour, f)? {
        Some(c) => format!("({:.2}, {:.2}, {:.2})", c[0], c[1], c[2]),
        None => "none".into(),
    })
}

fn main() -> Result<()> {
    let mut s = start()?;
    s.report("start: unit cube, 8 × 0.5 kg")?;
    split_an_edge(&mut s)?;
    s.report("after split_edge (the flag spreads to it)")?;

    // Triangulate: every piece keeps its face's colour and material.
    s.mesh.triangulate_all();
    s.report("after triangulate_all")?;

    poke_a_face(&mut s)?;
    s.report("after poke_face")?;
    flip_between_colours(&mut s)?;
    s.report("after flip_edge")?;
    collapse_at_selection(&mut s)?;
    s.report("after three collapses")?;

    s.mesh.validate()?;
    println!("the mesh is valid; total mass kept at 4.00 kg through every edit");
    Ok(())
}

/// A cube with a colour and a material per face, a mass on every vertex and
/// one selected corner.
fn start() -> Result<Session> {
    let mut mesh = meshloom::shapes::cube();
    // Colours interpolate ([f32; 3]'s own rule); materials never mix (u32:
    // Incompatible); mass is conserved (an explicit rule for f64); the
    // selection flag is contagious (bool).
    let colour = mesh.add_face_attr::<[f32; 3]>("colour")?;
    let material = mesh.add_face_attr::<u32>("material")?;
    let mass = mesh.add_attr_with_rule::<VertexKey, f64, Conserved>("mass")?;
    let selected = mesh.add_vertex_attr::<bool>("selected")?;
    let palette = [
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 1.0],
        [1.0, 0.0, 1.0],
    ];
    let faces: Vec<FaceKey> = mesh.faces().collect();
    for (i, &f) in faces.iter().enumerate() {
        mesh.set_attr(&colour, f, palette[i])?;
        mesh.set_attr(&material, f, (i % 2) as u32)?;
    }
    mesh.fill_attr(&mass, 0.5)?;
    mesh.fill_attr(&selected, false)?;
    let corner = mesh.vertices().next().expect("a cube has vertices");
    mesh.set_attr(&selected, corner, true)?;
    Ok(Session {
        mesh,
        colour,
        material,
        mass,
        selected,
    })
}

/// Split an edge a quarter of the way: the new vertex's position is
/// interpolated, it takes no mass (conserved), the faces keep colours.
fn split_an_edge(s: &mut Session) -> Result<()> {
    let e = s.mesh.edges().next().expect("edges");
    let [a, b] = s.mesh.edge(e)?.vertices();
    let m = s.mesh.split_edge(e, 0.25)?;
    println!(
        "  split_edge {a:?}-{b:?} at 0.25: new vertex at {:?}, mass {:?}",
        s.mesh.position(m)?,
        s.mesh.attr(&s.mass, m)?
    );
    Ok(())
}

/// Poke a face: the centre vertex sits at the centroid; the three new
/// triangles keep the colour.
fn poke_a_face(s: &mut Session) -> Result<()> {
    let f = s.mesh.faces().next().expect("faces");
    let before = colour_of(s, f)?;
    let c = s.mesh.poke_face(f)?;
    let pieces: Vec<String> = s
        .mesh
        .vertex(c)?
        .faces()
        .map(|g| colour_of(s, g))
        .collect::<Result<_>>()?;
    println!("  poke_face: colour {before} -> pieces {pieces:?}");
    Ok(())
}

/// Flip an edge between two faces of different colours: both faces merge
/// and split again, so their colours average while their materials
/// (different ids) are dropped rather than mixed.
fn flip_between_colours(s: &mut Session) -> Result<()> {
    let flip = s
        .mesh
        .edges()
        .find(|&e| {
            let [f, g] = s.mesh.edge(e).map(|x| x.faces()).unwrap_or([None, None]);
            let (Some(f), Some(g)) = (f, g) else {
                return false;
            };
            s.mesh.attr(&s.colour, f).ok() != s.mesh.attr(&s.colour, g).ok()
                && s.mesh.attr(&s.material, f).ok() != s.mesh.attr(&s.material, g).ok()
                && s.mesh.check_flip_edge(e).is_ok()
        })
        .expect("an edge between two colours and materials");
    let [f, g] = s.mesh.edge(flip)?.faces();
    let (f, g) = (f.expect("a face"), g.expect("a face"));
    println!(
        "  flip_edge {flip:?}: colours {} and {}",
        colour_of(s, f)?,
        colour_of(s, g)?
    );
    s.mesh.flip_edge(flip)?;
    println!(
        "    -> {} and {}, materials {:?} and {:?}",
        colour_of(s, f)?,
        colour_of(s, g)?,
        s.mesh.attr(&s.material, f)?,
        s.mesh.attr(&s.material, g)?
    );
    Ok(())
}

/// Collapse every edge at the selected corner, one after the other: the
/// masses pile up on the survivor, the selection flag spreads to it, and
/// the total mass never changes.
fn collapse_at_selection(s: &mut Session) -> Result<()> {
    for _ in 0..3 {
        let Some(v) = s
            .mesh
            .attr_view(&s.selected)?
            .iter()
            .find(|(_, sel)| **sel)
            .map(|(v, _)| v)
        else {
            break;
        };
        let Some(h) = s
            .mesh
            .vertex(v)?
            .outgoing()
            .find(|&h| s.mesh.check_collapse_edge(h).is_ok())
        else {
            break;
        };
        let kept = s.mesh.collapse_edge(h)?;
        println!(
            "  collapse_edge {v:?} into {kept:?}: survivor mass {:?}, selected {:?}",
            s.mesh.attr(&s.mass, kept)?,
            s.mesh.attr(&s.selected, kept)?
        );
    }
    Ok(())
}
