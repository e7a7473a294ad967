use super::*;
use crate::attr::{Conserved, FaceAttr, HalfedgeAttr};
use crate::journal::HistoryLimits;
use crate::model::testing::{field, fingerprint, mixed_meshes, next_random};
use crate::shapes;
use crate::Error;

fn opts(cuts: usize, twist: isize) -> BridgeOptions {
    BridgeOptions { cuts, twist }
}

/// The edge joining the `i`-th and `j`-th vertices (in key order).
fn edge(m: &Mesh, i: usize, j: usize) -> EdgeKey {
    let vs: Vec<VertexKey> = m.vertices().collect();
    let h = m.find_halfedge(vs[i], vs[j]).unwrap().unwrap();
    m.halfedge(h).unwrap().edge().key()
}

/// A hole's edges, in its order.
fn rim(m: &Mesh, hole: FaceKey) -> Vec<EdgeKey> {
    m.face(hole)
        .unwrap()
        .halfedges()
        .map(|h| m.halfedge(h).unwrap().edge().key())
        .collect()
}

/// Two strips of `na` and `nb` quads, at y in [0, 1] and [2, 3]; the
/// chains facing each other (y = 1 and y = 2).
fn strips(na: usize, nb: usize) -> (Mesh, Vec<EdgeKey>, Vec<EdgeKey>) {
    let mut p = Vec::new();
    let mut faces = Vec::new();
    for (y0, n) in [(0.0, na), (2.0, nb)] {
        let base = p.len() as u32;
        for y in [y0, y0 + 1.0] {
            for x in 0..=n {
                p.push([x as f64 * 3.0 / n as f64, y, 0.0]);
            }
        }
        let row = n as u32 + 1;
        for x in 0..n as u32 {
            faces.push(vec![
                base + x,
                base + x + 1,
                base + row + x + 1,
                base + row + x,
            ]);
        }
    }
    let m = Mesh::from_polygons(&p, &faces).unwrap();
    let a = (0..na).map(|x| edge(&m, na + 1 + x, na + 2 + x)).collect();
    let s = 2 * (na + 1);
    let b = (0..nb).map(|x| edge(&m, s + x, s + x + 1)).collect();
    (m, a, b)
}

/// Open tubes (no caps) of `n` quads around the z axis, one per `(n, z)`
/// from z to z + 1; each leaves two holes.
fn tubes(specs: &[(usize, f64)]) -> Mesh {
    let mut p = Vec::new();
    let mut faces = Vec::new();
    for &(n, z) in specs {
        let base = p.len() as u32;
        for dz in [0.0, 1.0] {
            for i in 0..n {
                let a = std::f64::consts::TAU * i as f64 / n as f64;
                p.push([a.cos(), a.sin(), z + dz]);
            }
        }
        let n = n as u32;
        for i in 0..n {
            let j = (i + 1) % n;
            faces.push(vec![base + i, base + j, base + n + j, base + n + i]);
        }
    }
    Mesh::from_polygons(&p, &faces).unwrap()
}

/// Corner UVs from the linear field (plus `shift` on faces with y > 1.5),
/// a material per strip, a conserved mass of 1 a face.
fn texture(m: &mut Mesh, shift: f64) -> (HalfedgeAttr<[f64; 2]>, FaceAttr<u32>) {
    let uv = m.add_halfedge_attr::<[f64; 2]>("uv").unwrap();
    let material = m.add_face_attr::<u32>("material").unwrap();
    let mass = m
        .add_attr_with_rule::<FaceKey, f64, Conserved>("mass")
        .unwrap();
    for f in m.faces().collect::<Vec<_>>() {
        let hs: Vec<_> = m.face(f).unwrap().halfedges().collect();
        let upper = m
            .face(f)
            .unwrap()
            .vertices()
            .any(|v| m.position(v).unwrap()[1] > 1.5);
        for h in hs {
            let p = m.halfedge(h).unwrap().origin().position().unwrap();
            let [u, v] = field(p);
            let u = if upper { u + shift } else { u };
            m.set_attr(&uv, h, [u, v]).unwrap();
        }
        m.set_attr(&material, f, u32::from(upper) + 1).unwrap();
        m.set_attr(&mass, f, 1.0).unwrap();
    }
    (uv, material)
}

fn mass_total(m: &Mesh) -> f64 {
    m.faces()
        .filter_map(|f| m.attr_value("mass", f).unwrap())
        .map(|x| x.as_f64().unwrap())
        .sum()
}

#[test]
fn two_strips_bridge_into_one_with_uvs_materials_and_mass() {
    for cuts in [0, 1, 3] {
        let (mut m, a, b) = strips(3, 3);
        let (uv, material) = texture(&mut m, 0.0);
        let made = m.bridge_loops(&a, &b, &opts(cuts, 0)).unwrap();
        m.validate().unwrap();
        assert_eq!(made.faces.len(), 3 * (cuts + 1));
        assert_eq!(made.vertices.len(), 4 * cuts);
        assert_eq!(made.edges.len(), 4 * (cuts + 1) + 3 * cuts);
        assert_eq!((m.face_count(), m.hole_count()), (6 + 3 * (cuts + 1), 1));
        assert_eq!(m.euler_characteristic(), 1);
        assert!(!made.closed);
        assert_eq!(made.holes.len(), 1);
        // The new vertices sit evenly on the rungs, x matching.
        for &v in &made.vertices {
            let p = m.position(v).unwrap();
            let y = (p[1] - 1.0) * (cuts + 1) as f64;
            assert!((y - y.round()).abs() < 1e-12, "{p:?}");
        }
        // One island, the linear field everywhere (copied at the loops,
        // interpolated at the cuts); the band takes loop A's material.
        for h in m
            .halfedges()
            .filter(|&h| !m.halfedge(h).unwrap().is_boundary())
        {
            let p = m.halfedge(h).unwrap().origin().position().unwrap();
            let got = *m.attr(&uv, h).unwrap().unwrap();
            let want = field(p);
            assert!((got[0] - want[0]).abs() < 1e-12 && (got[1] - want[1]).abs() < 1e-12);
        }
        for &f in &made.faces {
            assert_eq!(m.attr(&material, f).unwrap(), Some(&1));
        }
        // New faces are not made of mass (conserved: nothing created).
        assert_eq!(mass_total(&m), 6.0);
    }
}

#[test]
fn a_seam_between_the_loops_stays_on_each_side() {
    let (mut m, a, b) = strips(3, 3);
    let (uv, _) = texture(&mut m, 10.0);
    let made = m.bridge_loops(&a, &b, &opts(0, 0)).unwrap();
    m.validate().unwrap();
    // Each band corner copies the face across the loop edge at its vertex:
    // loop A's island at y = 1, loop B's (shifted) at y = 2.
    for &f in &made.faces {
        for h in m.face(f).unwrap().halfedges() {
            let p = m.halfedge(h).unwrap().origin().position().unwrap();
            let got = *m.attr(&uv, h).unwrap().unwrap();
            let shift = if p[1] > 1.5 { 10.0 } else { 0.0 };
            assert_eq!(got, [field(p)[0] + shift, field(p)[1]], "{p:?}");
        }
    }
}

#[test]
fn circles_of_eight_bridge_into_a_tube_with_and_without_cuts() {
    for (cuts, added) in [(0, 8), (2, 24)] {
        // Two tubes, at z in [0, 1] and [2, 3]: their rims at 1 and 2.
        let mut m = tubes(&[(8, 0.0), (8, 2.0)]);
        let at = |m: &Mesh, z: f64| {
            m.holes()
                .find(|&h| {
                    let v = m.face(h).unwrap().vertices().next().unwrap();
                    m.position(v).unwrap()[2] == z
                })
                .unwrap()
        };
        let holes = [at(&m, 1.0), at(&m, 2.0)];
        let (f0, v0, e0) = (m.face_count(), m.vertex_count(), m.edge_count());
        let made = m
            .bridge_loops(&rim(&m, holes[0]), &rim(&m, holes[1]), &opts(cuts, 0))
            .unwrap();
        m.validate().unwrap();
        assert_eq!(m.face_count(), f0 + added);
        assert_eq!(m.vertex_count(), v0 + 8 * cuts);
        assert_eq!(m.edge_count(), e0 + 8 * (cuts + 1) + 8 * cuts);
        assert!(made.closed && made.holes.is_empty());
        assert_eq!((m.hole_count(), m.euler_characteristic()), (2, 0));
        for h in holes {
            assert!(m.face(h).is_err());
        }
    }
}

#[test]
fn two_holes_of_a_sphere_bridge_into_a_torus() {
    let mut m = shapes::uv_sphere(8, 6);
    // Two quads on opposite sides of the equator.
    let quads: Vec<FaceKey> = m
        .faces()
        .filter(|&f| m.face(f).unwrap().degree() == 4)
        .collect();
    let centre = |m: &Mesh, f: FaceKey| {
        let ps: Vec<V3> = m
            .face(f)
            .unwrap()
            .vertices()
            .map(|v| m.position(v).unwrap())
            .collect();
        ps.iter().fold([0.0; 3], |s, &p| vec3::add(s, p))
    };
    let first = quads[0];
    let c0 = centre(&m, first);
    let far = *quads
        .iter()
        .max_by(|&&x, &&y| {
            let (dx, dy) = (
                vec3::dist2(centre(&m, x), c0),
                vec3::dist2(centre(&m, y), c0),
            );
            dx.total_cmp(&dy)
        })
        .unwrap();
    let ha = m.remove_face(first).unwrap()[0];
    let hb = m.remove_face(far).unwrap()[0];
    assert_eq!(m.euler_characteristic(), 0);
    let made = m
        .bridge_loops(&rim(&m, ha), &rim(&m, hb), &opts(1, 1))
        .unwrap();
    m.validate().unwrap();
    assert_eq!(made.faces.len(), 8);
    assert!(m.is_closed());
    assert_eq!(m.euler_characteristic(), 0); // genus 1
}

#[test]
fn loops_of_six_and_eight_get_quads_and_two_triangles() {
    let m = tubes(&[(6, 0.0), (8, 2.0)]);
    let holes: Vec<FaceKey> = m.holes().collect();
    let deg = |m: &Mesh, h: FaceKey| m.face(h).unwrap().degree();
    // The six-loop at z = 1 and the eight-loop at z = 2.
    let z = |m: &Mesh, h: FaceKey| {
        let v = m.face(h).unwrap().vertices().next().unwrap();
        m.position(v).unwrap()[2]
    };
    let a = *holes
        .iter()
        .find(|&&h| deg(&m, h) == 6 && z(&m, h) == 1.0)
        .unwrap();
    let b = *holes
        .iter()
        .find(|&&h| deg(&m, h) == 8 && z(&m, h) == 2.0)
        .unwrap();
    for (x, y) in [(a, b), (b, a)] {
        let mut m = m.clone();
        let f0 = m.face_count();
        let made = m
            .bridge_loops(&rim(&m, x), &rim(&m, y), &opts(0, 0))
            .unwrap();
        m.validate().unwrap();
        let degrees: Vec<usize> = made
            .faces
            .iter()
            .map(|&f| m.face(f).unwrap().degree())
            .collect();
        assert_eq!(degrees.iter().filter(|&&d| d == 4).count(), 6);
        assert_eq!(degrees.iter().filter(|&&d| d == 3).count(), 2);
        assert_eq!((m.face_count(), m.hole_count()), (f0 + 8, 2));
        assert_eq!(m.euler_characteristic(), 0);
        // With cuts: the triangles only where the cells meet the short loop.
        let mut m2 = tubes(&[(6, 0.0), (8, 2.0)]);
        let made = m2
            .bridge_loops(&rim(&m2, x), &rim(&m2, y), &opts(2, 3))
            .unwrap();
        m2.validate().unwrap();
        assert_eq!(made.faces.len(), 24);
        assert_eq!(made.vertices.len(), 16);
    }
    // Open chains of 3 and 5 edges.
    let (mut m, a, b) = strips(3, 5);
    let made = m.bridge_loops(&a, &b, &opts(1, 0)).unwrap();
    m.validate().unwrap();
    assert_eq!(made.faces.len(), 10);
    assert_eq!(m.euler_characteristic(), 1);
}

#[test]
fn chains_on_one_hole_split_it_in_two() {
    let mut m = shapes::grid(3, 3, shapes::GridFaces::Quads);
    // The middle edges of the bottom and top sides.
    let (a, b) = (edge(&m, 1, 2), edge(&m, 13, 14));
    let made = m.bridge_loops(&[a], &[b], &opts(0, 0)).unwrap();
    m.validate().unwrap();
    assert_eq!(
        (made.faces.len(), made.holes.len(), m.hole_count()),
        (1, 2, 2)
    );
    assert_eq!(m.euler_characteristic(), 0);
}

#[test]
fn refusals_change_nothing_and_a_bridge_is_one_undo_step() {
    let (mut m, a, b) = strips(3, 3);
    texture(&mut m, 0.0);
    m.history_mut().enable(HistoryLimits::default());
    let before = fingerprint(&m);
    let inner = edge(&m, 1, 5);
    let refused = |m: &mut Mesh, x: &[EdgeKey], y: &[EdgeKey], o: BridgeOptions| {
        let err = m.bridge_loops(x, y, &o).unwrap_err();
        assert_eq!(m.check_bridge_loops(x, y, &o).unwrap_err(), err);
        match err {
            Error::Refused { reason, .. } => reason,
            e => panic!("{e:?}"),
        }
    };
    let cases: Vec<(Vec<EdgeKey>, Vec<EdgeKey>, BridgeOptions, Refusal)> = vec![
        (vec![], b.clone(), opts(0, 0), Refusal::Empty),
        (vec![inner], b.clone(), opts(0, 0), Refusal::Boundary),
        (
            vec![a[0], a[2]],
            b.clone(),
            opts(0, 0),
            Refusal::Parameter("the edges must be one run of consecutive boundary edges"),
        ),
        (a.clone(), a.clone(), opts(0, 0), Refusal::Adjacent),
        (
            a.clone(),
            b.clone(),
            opts(MAX_BRIDGE_CUTS + 1, 0),
            Refusal::Parameter("cuts must be at most 4096"),
        ),
    ];
    for (x, y, o, want) in cases {
        assert_eq!(refused(&mut m, &x, &y, o), want);
        assert_eq!(fingerprint(&m), before);
    }
    // A rung onto an existing edge: two quad holes one quad apart.
    let mut g = shapes::grid(5, 3, shapes::GridFaces::Quads);
    let fs: Vec<FaceKey> = g.faces().collect();
    let h0 = g.remove_face(fs[6]).unwrap()[0];
    let h2 = g.remove_face(fs[8]).unwrap()[0];
    assert_eq!(g.hole_count(), 3);
    let gb = fingerprint(&g);
    let (x, y) = (rim(&g, h0), rim(&g, h2));
    assert_eq!(refused(&mut g, &x, &y, opts(0, 0)), Refusal::EdgeExists);
    assert_eq!(fingerprint(&g), gb);
    // Closed with open.
    let mut t = tubes(&[(4, 0.0)]);
    let h = t.holes().next().unwrap();
    let loop_a = rim(&t, h);
    let other: Vec<EdgeKey> = t.holes().nth(1).map(|h| rim(&t, h)).unwrap();
    let tb = fingerprint(&t);
    assert!(matches!(
        refused(&mut t, &loop_a, &other[..2], opts(0, 0)),
        Refusal::Parameter(_)
    ));
    assert_eq!(fingerprint(&t), tb);
    // One undo step, exact.
    let undo = m.history().undo_len();
    m.bridge_loops(&a, &b, &opts(2, 0)).unwrap();
    m.validate().unwrap();
    assert_eq!(m.history().undo_len(), undo + 1);
    assert!(m.undo());
    assert_eq!(fingerprint(&m), before);
    // A stale edge.
    let (mut s, a, b) = strips(1, 1);
    s.remove_face(s.faces().next().unwrap()).unwrap();
    assert!(matches!(
        s.bridge_loops(&a, &b, &opts(0, 0)),
        Err(Error::StaleKey { .. })
    ));
}

#[test]
fn random_hole_selections_bridge_and_validate_or_change_nothing() {
    let mut seed = 0x9e37_79b9_7f4a_7c15u64;
    for mesh in mixed_meshes() {
        for _ in 0..30 {
            let mut m = mesh.clone();
            // Open a few holes, then pick two runs of boundary edges.
            let faces: Vec<FaceKey> = m.faces().collect();
            for _ in 0..3 {
                let f = faces[next_random(&mut seed) as usize % faces.len()];
                if m.face(f).is_ok() {
                    let _ = m.remove_face(f);
                }
            }
            let holes: Vec<FaceKey> = m.holes().collect();
            let pick = |m: &Mesh, seed: &mut u64| -> Vec<EdgeKey> {
                let h = holes[next_random(seed) as usize % holes.len()];
                let all = rim(m, h);
                let start = next_random(seed) as usize % all.len();
                let len = 1 + next_random(seed) as usize % all.len();
                (0..len).map(|i| all[(start + i) % all.len()]).collect()
            };
            let (x, y) = (pick(&m, &mut seed), pick(&m, &mut seed));
            let o = opts(
                next_random(&mut seed) as usize % 3,
                next_random(&mut seed) as isize % 5,
            );
            let before = fingerprint(&m);
            let (f0, chi) = (m.face_count(), m.euler_characteristic());
            match m.bridge_loops(&x, &y, &o) {
                Ok(made) => {
                    m.validate().unwrap();
                    assert_eq!(m.face_count(), f0 + made.faces.len());
                    // Two holes into one band: χ drops by the new edges
                    // less the new vertices and faces (0 for closed loops
                    // with the holes gone, −1 for open chains).
                    let want = if made.closed { chi } else { chi - 1 };
                    assert_eq!(m.euler_characteristic(), want);
                }
                Err(Error::Refused { .. }) => assert_eq!(fingerprint(&m), before),
                Err(e) => panic!("{e:?}"),
            }
        }
    }
}
