use super::*;
use crate::attr::{Conserved, HalfedgeAttr};
use crate::journal::HistoryLimits;
use crate::model::testing::{field, fingerprint, mixed_meshes, next_random, random_faces};
use crate::model::Delimit;
use crate::shapes::{self, GridFaces};
use crate::{Error, HalfedgeKey};

/// The edges of `mesh` whose two ends satisfy `keep`.
fn edges_where(mesh: &Mesh, keep: impl Fn([f64; 3], [f64; 3]) -> bool) -> Vec<EdgeKey> {
    mesh.edges()
        .filter(|&e| {
            let [a, b] = mesh
                .edge(e)
                .unwrap()
                .vertices()
                .map(|v| mesh.position(v).unwrap());
            keep(a, b)
        })
        .collect()
}

/// A 4 × 4 quad grid with corner UVs in two islands (y below and above
/// 2, the upper one shifted by 10 in u), a material per row and a
/// conserved edge quantity of 1 an edge.
fn textured_grid() -> (Mesh, HalfedgeAttr<[f64; 2]>) {
    let mut mesh = shapes::grid(4, 4, GridFaces::Quads);
    let uv = mesh.add_halfedge_attr::<[f64; 2]>("uv").unwrap();
    let material = mesh.add_face_attr::<u32>("material").unwrap();
    let length = mesh
        .add_attr_with_rule::<EdgeKey, f64, Conserved>("length")
        .unwrap();
    for f in mesh.faces().collect::<Vec<_>>() {
        let ys: Vec<f64> = mesh
            .face(f)
            .unwrap()
            .vertices()
            .map(|v| mesh.position(v).unwrap()[1])
            .collect();
        let y = ys.iter().sum::<f64>() / 4.0;
        mesh.set_attr(&material, f, y as u32).unwrap();
        let hs: Vec<HalfedgeKey> = mesh.face(f).unwrap().halfedges().collect();
        for h in hs {
            let p = mesh.halfedge(h).unwrap().origin().position().unwrap();
            let shift = if y < 2.0 { 0.0 } else { 10.0 };
            let [u, v] = field(p);
            mesh.set_attr(&uv, h, [u + shift, v]).unwrap();
        }
    }
    for e in mesh.edges().collect::<Vec<_>>() {
        mesh.set_attr(&length, e, 1.0).unwrap();
    }
    (mesh, uv)
}

/// Whether every vertex's corners agree on `uv` (no seam left inside).
fn no_seams(mesh: &Mesh, uv: &HalfedgeAttr<[f64; 2]>) -> bool {
    mesh.vertices().all(|v| {
        let values: Vec<[f64; 2]> = mesh
            .vertex(v)
            .unwrap()
            .outgoing()
            .filter(|&o| !mesh.halfedge(o).unwrap().is_boundary())
            .map(|o| *mesh.attr(uv, o).unwrap().unwrap())
            .collect();
        values.windows(2).all(|w| w[0] == w[1])
    })
}

#[test]
fn a_uv_seam_from_boundary_to_boundary_rips_the_grid_in_two_keeping_every_column() {
    let (mut mesh, uv) = textured_grid();
    assert!(!no_seams(&mesh, &uv));
    let seams = Delimit {
        seams: Some("uv".into()),
        ..Delimit::default()
    };
    let chosen = seams.edges(&mesh).unwrap();
    // 16 boundary edges and the 4 of the seam at y = 2.
    assert_eq!(chosen.len(), 20);
    let materials: Vec<_> = mesh
        .faces()
        .map(|f| mesh.attr_value("material", f).unwrap())
        .collect();
    let made = mesh.split_edges(&chosen).unwrap();
    mesh.validate().unwrap();
    assert_eq!((made.edges.len(), made.vertices.len()), (4, 5));
    assert_eq!(
        (mesh.vertex_count(), mesh.edge_count(), mesh.face_count()),
        (25 + 5, 40 + 4, 16)
    );
    // One hole: the old boundary joined to the cut, then cut apart.
    assert_eq!(mesh.holes().count(), 2);
    assert_eq!(mesh.split_components(true).len(), 2);
    assert!(no_seams(&mesh, &uv));
    let after: Vec<_> = mesh
        .faces()
        .map(|f| mesh.attr_value("material", f).unwrap())
        .collect();
    assert_eq!(after, materials);
    let length = mesh
        .attr_handle::<EdgeKey, f64, Conserved>("length")
        .unwrap();
    let total: f64 = mesh
        .edges()
        .map(|e| *mesh.attr(&length, e).unwrap().unwrap())
        .sum();
    assert_eq!(total, 40.0);
    // Positions: every copy sits where its vertex is.
    for v in made.vertices {
        let p = mesh.position(v).unwrap();
        assert_eq!(p[1], 2.0);
    }
}

#[test]
fn a_cross_inside_a_grid_splits_its_centre_in_four_and_leaves_its_tips() {
    let mut mesh = shapes::grid(4, 4, GridFaces::Quads);
    let chosen = edges_where(&mesh, |a, b| {
        let near = |p: [f64; 3]| (p[0] - 2.0).abs() + (p[1] - 2.0).abs() <= 1.0;
        near(a) && near(b)
    });
    assert_eq!(chosen.len(), 4);
    let made = mesh.split_edges(&chosen).unwrap();
    mesh.validate().unwrap();
    assert_eq!((made.edges.len(), made.vertices.len()), (4, 3));
    assert_eq!(
        (mesh.vertex_count(), mesh.edge_count(), mesh.face_count()),
        (28, 44, 16)
    );
    // The outer boundary and one hole of 8 edges round the cross.
    let mut sizes: Vec<usize> = mesh
        .holes()
        .map(|h| mesh.face(h).unwrap().halfedges().count())
        .collect();
    sizes.sort();
    assert_eq!(sizes, [8, 16]);
}

#[test]
fn a_closed_loop_cuts_a_sphere_in_two() {
    let mut sphere = shapes::uv_sphere(8, 4);
    let equator = edges_where(&sphere, |a, b| a[2].abs() < 1e-9 && b[2].abs() < 1e-9);
    assert_eq!(equator.len(), 8);
    let made = sphere.split_edges(&equator).unwrap();
    sphere.validate().unwrap();
    assert_eq!((made.holes.len(), made.vertices.len()), (2, 8));
    let parts = sphere.split_components(true);
    assert_eq!(parts.len(), 2);
    assert_eq!(parts[0].face_count() + parts[1].face_count(), 32);
}

#[test]
fn refusals_change_nothing_and_a_split_is_one_undo_step() {
    let (mut mesh, _) = textured_grid();
    mesh.history_mut().enable(HistoryLimits::default());
    let before = fingerprint(&mesh);
    // A chosen edge alone inside the surface.
    let alone = edges_where(&mesh, |a, b| {
        let inside = |p: [f64; 3]| (1.0..=3.0).contains(&p[0]) && (1.0..=3.0).contains(&p[1]);
        inside(a) && inside(b)
    })[0];
    let err = mesh.split_edges(&[alone]).unwrap_err();
    assert!(matches!(
        err,
        Error::Refused {
            reason: Refusal::Parameter(_),
            ..
        }
    ));
    assert!(mesh.check_split_edges(&[alone]).is_err());
    // Boundary edges only: nothing to do, nothing changes.
    let boundary: Vec<EdgeKey> = mesh
        .edges()
        .filter(|&e| mesh.edge(e).unwrap().is_boundary())
        .collect();
    assert_eq!(mesh.split_edges(&boundary).unwrap(), SplitEdges::default());
    assert_eq!(fingerprint(&mesh), before);
    let seams = Delimit {
        seams: Some("uv".into()),
        ..Delimit::default()
    };
    let chosen = seams.edges(&mesh).unwrap();
    let undo = mesh.history().undo_len();
    mesh.split_edges(&chosen).unwrap();
    assert_eq!(mesh.history().undo_len(), undo + 1);
    assert!(mesh.undo());
    assert_eq!(fingerprint(&mesh), before);
    // A stale key.
    let made = mesh.split_edges(&chosen).unwrap();
    assert!(mesh.undo());
    assert!(matches!(
        mesh.split_edges(&made.edges),
        Err(Error::StaleKey(_))
    ));
}

#[test]
fn random_edge_selections_split_and_validate_or_change_nothing() {
    let mut seed = 0x5851_f42d_4c95_7f2du64;
    let mut done = 0;
    for mesh in mixed_meshes() {
        for round in 0..60 {
            // Odd rounds: the outline of a random region (closed loops and
            // paths between holes); even rounds: any edges.
            let chosen: Vec<EdgeKey> = if round % 2 == 1 {
                let region: HashSet<FaceKey> = random_faces(&mesh, &mut seed).into_iter().collect();
                mesh.edges()
                    .filter(|&e| {
                        let [a, b] = mesh.edge(e).unwrap().faces();
                        let inside = |f: Option<FaceKey>| f.is_some_and(|f| region.contains(&f));
                        inside(a) != inside(b)
                    })
                    .collect()
            } else {
                mesh.edges()
                    .filter(|_| next_random(&mut seed) % (2 + round % 7) == 0)
                    .collect()
            };
            let mut m = mesh.clone();
            match m.split_edges(&chosen) {
                Ok(made) => {
                    m.validate().unwrap();
                    assert_eq!(m.face_count(), mesh.face_count());
                    assert_eq!(m.edge_count(), mesh.edge_count() + made.edges.len());
                    assert_eq!(m.vertex_count(), mesh.vertex_count() + made.vertices.len());
                    done += 1;
                }
                Err(e) => {
                    assert!(matches!(e, Error::Refused { .. }), "{e:?}");
                    assert_eq!(fingerprint(&m), fingerprint(&mesh));
                }
            }
        }
    }
    assert!(done > 120, "only {done} of 240 selections split");
}
