use super::*;
use crate::attr::{Conserved, HalfedgeAttr};
use crate::journal::HistoryLimits;
use crate::model::testing::{field, fingerprint, mixed_meshes, random_faces};
use crate::shapes::{self, GridFaces};
use crate::Error;

/// A 4 × 4 quad grid with corner UVs from [`field`], a material per face
/// and a conserved face quantity of 1 a face.
fn textured_grid() -> (Mesh, HalfedgeAttr<[f64; 2]>) {
    let mut mesh = shapes::grid(4, 4, GridFaces::Quads);
    let uv = mesh.add_halfedge_attr::<[f64; 2]>("uv").unwrap();
    let material = mesh.add_face_attr::<u32>("material").unwrap();
    let mass = mesh
        .add_attr_with_rule::<FaceKey, f64, Conserved>("mass")
        .unwrap();
    for (i, f) in mesh.faces().collect::<Vec<_>>().into_iter().enumerate() {
        mesh.set_attr(&material, f, i as u32).unwrap();
        mesh.set_attr(&mass, f, 1.0).unwrap();
        for h in mesh.face(f).unwrap().halfedges().collect::<Vec<_>>() {
            let p = mesh.halfedge(h).unwrap().origin().position().unwrap();
            mesh.set_attr(&uv, h, field(p)).unwrap();
        }
    }
    (mesh, uv)
}

/// The faces of `mesh` whose centre lies in `[x0, x1] × [y0, y1]`.
fn block(mesh: &Mesh, x: [f64; 2], y: [f64; 2]) -> Vec<FaceKey> {
    mesh.faces()
        .filter(|&f| {
            let ps: Vec<_> = mesh
                .face(f)
                .unwrap()
                .vertices()
                .map(|v| mesh.position(v).unwrap())
                .collect();
            let n = ps.len() as f64;
            let c = [0, 1].map(|k| ps.iter().map(|p| p[k]).sum::<f64>() / n);
            (x[0]..=x[1]).contains(&c[0]) && (y[0]..=y[1]).contains(&c[1])
        })
        .collect()
}

#[test]
fn a_block_copies_with_every_column_and_a_hole_round_it() {
    let (mut mesh, uv) = textured_grid();
    let chosen = block(&mesh, [1.0, 3.0], [1.0, 3.0]);
    assert_eq!(chosen.len(), 4);
    let made = mesh.duplicate_faces(&chosen).unwrap();
    mesh.validate().unwrap();
    assert_eq!(
        (
            made.vertices.len(),
            made.edges.len(),
            made.faces.len(),
            made.holes.len()
        ),
        (9, 12, 4, 1)
    );
    assert_eq!(
        (mesh.vertex_count(), mesh.edge_count(), mesh.face_count()),
        (25 + 9, 40 + 12, 20)
    );
    assert_eq!(mesh.split_components(false).len(), 2);
    for &(src, copy) in &made.faces {
        assert_eq!(
            mesh.attr_value("material", src).unwrap(),
            mesh.attr_value("material", copy).unwrap()
        );
        let corners = |f: FaceKey| -> Vec<([f64; 3], [f64; 2])> {
            mesh.face(f)
                .unwrap()
                .halfedges()
                .map(|h| {
                    let p = mesh.halfedge(h).unwrap().origin().position().unwrap();
                    (p, *mesh.attr(&uv, h).unwrap().unwrap())
                })
                .collect()
        };
        assert_eq!(corners(src), corners(copy));
    }
    let mass = mesh.attr_handle::<FaceKey, f64, Conserved>("mass").unwrap();
    let total: f64 = mesh
        .faces()
        .map(|f| *mesh.attr(&mass, f).unwrap().unwrap())
        .sum();
    assert_eq!(total, 20.0);
    // The hole's corners carry no UV.
    let hole = made.holes[0];
    assert_eq!(mesh.face(hole).unwrap().halfedges().count(), 8);
    assert!(mesh
        .face(hole)
        .unwrap()
        .halfedges()
        .all(|h| mesh.attr(&uv, h).unwrap().is_none()));
}

#[test]
fn faces_meeting_at_a_corner_get_a_vertex_copy_each_and_a_closed_mesh_copies_closed() {
    let mut mesh = shapes::grid(2, 2, GridFaces::Quads);
    let diagonal = [
        block(&mesh, [0.0, 1.0], [0.0, 1.0]),
        block(&mesh, [1.0, 2.0], [1.0, 2.0]),
    ]
    .concat();
    let made = mesh.duplicate_faces(&diagonal).unwrap();
    mesh.validate().unwrap();
    assert_eq!((made.vertices.len(), made.holes.len()), (8, 2));
    let mut cube = shapes::cube();
    let all: Vec<FaceKey> = cube.faces().collect();
    let made = cube.duplicate_faces(&all).unwrap();
    cube.validate().unwrap();
    assert!(made.holes.is_empty());
    assert_eq!(
        (cube.vertex_count(), cube.face_count(), cube.hole_count()),
        (16, 12, 0)
    );
}

#[test]
fn refusals_change_nothing_and_a_duplicate_is_one_undo_step() {
    let (mut mesh, _) = textured_grid();
    mesh.history_mut().enable(HistoryLimits::default());
    let before = fingerprint(&mesh);
    let hole = mesh.holes().next().unwrap();
    let f = mesh.faces().next().unwrap();
    for faces in [vec![], vec![f, hole]] {
        let err = mesh.duplicate_faces(&faces).unwrap_err();
        assert!(matches!(err, Error::Refused { .. }), "{err:?}");
        assert!(mesh.separate(&faces).is_err());
        assert_eq!(fingerprint(&mesh), before);
    }
    let undo = mesh.history().undo_len();
    let made = mesh.duplicate_faces(&[f]).unwrap();
    assert_eq!(mesh.history().undo_len(), undo + 1);
    assert!(mesh.undo());
    assert_eq!(fingerprint(&mesh), before);
    assert!(matches!(
        mesh.duplicate_faces(&[made.faces[0].1]),
        Err(Error::StaleKey(_))
    ));
    // Separate: the part keeps the faces with their keys and values, the
    // source loses them in one step.
    let chosen = block(&mesh, [0.0, 2.0], [0.0, 4.0]);
    let materials: Vec<_> = chosen
        .iter()
        .map(|&f| mesh.attr_value("material", f).unwrap())
        .collect();
    let part = mesh.separate(&chosen).unwrap();
    part.validate().unwrap();
    mesh.validate().unwrap();
    assert_eq!((part.face_count(), mesh.face_count()), (8, 8));
    for (&f, m) in chosen.iter().zip(materials) {
        assert!(part.contains_face(f) && !mesh.contains_face(f));
        assert_eq!(part.attr_value("material", f).unwrap(), m);
    }
    assert_eq!(mesh.history().undo_len(), undo + 1);
    assert!(mesh.undo());
    assert_eq!(fingerprint(&mesh), before);
}

#[test]
fn random_selections_duplicate_and_validate() {
    let mut seed = 0x2545_f491_4f6c_dd1du64;
    for mesh in mixed_meshes() {
        for _ in 0..30 {
            let faces = random_faces(&mesh, &mut seed);
            if faces.is_empty() {
                continue;
            }
            let mut m = mesh.clone();
            let made = m.duplicate_faces(&faces).unwrap();
            m.validate().unwrap();
            assert_eq!(m.face_count(), mesh.face_count() + faces.len());
            assert_eq!(m.vertex_count(), mesh.vertex_count() + made.vertices.len());
            assert_eq!(m.edge_count(), mesh.edge_count() + made.edges.len());
            let mut part = mesh.clone();
            let piece = part.separate(&faces).unwrap();
            piece.validate().unwrap();
            part.validate().unwrap();
            assert_eq!(piece.face_count() + part.face_count(), mesh.face_count());
        }
    }
}
