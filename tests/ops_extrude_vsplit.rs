//! extrude_face, split_vertex, split_components.

mod common;
use common::*;
use meshloom::{shapes, Error, Mesh, Refusal};

#[test]
fn extrude_a_cube_face() {
    let mut m = shapes::cube();
    let t = add_totals(&mut m);
    let f = m.faces().next().unwrap();
    let before: Vec<[f64; 3]> = m
        .face(f)
        .unwrap()
        .vertices()
        .map(|v| m.position(v).unwrap())
        .collect();
    let sides = checked(&mut m, |m| m.extrude_face(f, 1.5)).unwrap();
    assert_eq!(sides.len(), 4);
    assert_eq!(counts(&m), (12, 20, 10, 0));
    assert_eq!(m.euler_characteristic(), 2);
    assert!(sides.iter().all(|&s| m.face(s).unwrap().degree() == 4));
    let after: Vec<[f64; 3]> = m
        .face(f)
        .unwrap()
        .vertices()
        .map(|v| m.position(v).unwrap())
        .collect();
    // Every cap corner moved 1.5 along the same unit vector.
    for (p, q) in before.iter().zip(&after) {
        let d = ((q[0] - p[0]).powi(2) + (q[1] - p[1]).powi(2) + (q[2] - p[2]).powi(2)).sqrt();
        assert!((d - 1.5).abs() < 1e-12);
    }
    assert_eq!(face_total(&m, &t), 6.0);
    let hole = {
        let mut l = l_shape();
        let h = l.holes().next().unwrap();
        matches!(
            checked(&mut l, |m| m.extrude_face(h, 1.0)),
            Err(Error::Refused {
                reason: Refusal::Hole,
                ..
            })
        )
    };
    assert!(hole);
    assert!(checked(&mut m, |m| m.extrude_face(f, f64::NAN)).is_err());
}

#[test]
fn extrude_without_positions_and_on_the_boundary() {
    let mut m = Mesh::from_faces(4, &[[0u32, 1, 2, 3]]).unwrap();
    let f = m.faces().next().unwrap();
    checked(&mut m, |m| m.extrude_face(f, 1.0)).unwrap();
    assert_eq!(counts(&m), (8, 12, 5, 1));
    let mut m = l_shape();
    let f = m.faces().next().unwrap();
    checked(&mut m, |m| m.extrude_face(f, -0.5)).unwrap();
    assert_eq!(m.hole_count(), 1);
    assert_eq!(m.euler_characteristic(), 1);
}

#[test]
fn split_vertex_undoes_collapse() {
    for mut m in [shapes::icosahedron(), one_ring(), open_cone()] {
        let original = counts(&m);
        let h0 = m
            .halfedges()
            .find(|&h| {
                let hv = m.halfedge(h).unwrap();
                !hv.face().is_hole()
                    && !hv.twin().face().is_hole()
                    && m.check_collapse_edge(h).is_ok()
            })
            .unwrap();
        let hv = m.halfedge(h0).unwrap();
        let (c, d) = (hv.next().dest().key(), hv.twin().next().dest().key());
        let b = m.collapse_edge(h0).unwrap();
        let hc = m.find_halfedge(b, c).unwrap().unwrap();
        let hd = m.find_halfedge(b, d).unwrap().unwrap();
        let h = checked(&mut m, |m| m.split_vertex(hc, hd)).unwrap();
        assert_eq!(counts(&m), original);
        assert_eq!(m.halfedge(h).unwrap().dest().key(), b);
        assert_eq!(m.halfedge(h).unwrap().face().degree(), 3);
        assert_eq!(m.halfedge(h).unwrap().twin().face().degree(), 3);
        // And collapsing the new edge again is allowed.
        checked(&mut m, |m| m.collapse_edge(h)).unwrap();
    }
}

#[test]
fn split_vertex_refusals() {
    let mut m = shapes::icosahedron();
    let v: Vec<_> = m.vertices().collect();
    let a = m.vertex(v[0]).unwrap().outgoing().next().unwrap();
    let b = m.vertex(v[1]).unwrap().outgoing().next().unwrap();
    assert!(matches!(
        checked(&mut m, |m| m.split_vertex(a, b)),
        Err(Error::Refused {
            reason: Refusal::NotAdjacent,
            ..
        })
    ));
    assert!(matches!(
        checked(&mut m, |m| m.split_vertex(a, a)),
        Err(Error::Refused {
            reason: Refusal::Adjacent,
            ..
        })
    ));
    // Adjacent half-edges around a vertex: a new vertex of degree 3.
    let outs: Vec<_> = m.vertex(v[0]).unwrap().outgoing().collect();
    checked(&mut m, |m| m.split_vertex(outs[1], outs[0])).unwrap();
    assert_eq!(m.euler_characteristic(), 2);
}

#[test]
fn split_components_of_real_and_named_meshes() {
    let two = Mesh::from_faces(7, &[vec![0u32, 1, 2], vec![3, 4, 5, 6]]).unwrap();
    let parts = two.split_components(true);
    assert_eq!(parts.len(), 2);
    assert_eq!(counts(&parts[0]), (3, 3, 1, 1));
    assert_eq!(counts(&parts[1]), (4, 4, 1, 1));
    assert_eq!(parts[1].slot_counts(), [4, 8, 4, 2]);
    // The bowtie is one piece (joined at a vertex).
    assert_eq!(bowtie().split_components(false).len(), 1);
    let m = read_off(&mesh_path("boundary/cgal_quads_to_stitch.off"));
    let parts = m.split_components(true);
    assert_eq!(parts.len(), 2);
    let total: usize = parts.iter().map(|p| p.face_count()).sum();
    assert_eq!(total, m.face_count());
    for p in &parts {
        p.validate().unwrap();
    }
    assert!(Mesh::new().split_components(false).is_empty());
}

/// A zero-area face has no normal to move along: the refusal says so and
/// names the face (it said "fewer than three sides").
#[test]
fn extrude_of_a_zero_area_face_names_it_and_the_reason() {
    let p = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]];
    let mut m = Mesh::from_polygons(&p, &[[0u32, 1, 2]]).unwrap();
    let f = m.faces().next().unwrap();
    let err = m.extrude_face(f, 1.0).unwrap_err();
    assert_eq!(
        err,
        Error::Refused {
            op: "extrude_face",
            key: f.into(),
            reason: Refusal::ZeroArea,
        }
    );
    assert!(err.to_string().contains("zero area"), "{err}");
}

/// Buffers, files and mesh edits mix in one function with `?`.
#[test]
fn any_error_takes_buffer_errors() {
    use meshloom::buffers::{FromBuffersOptions, Indices, TriangleBufferOptions};
    fn round_trip(mesh: &Mesh, corrupt: bool) -> Result<usize, meshloom::AnyError> {
        let mut b = mesh.to_triangle_buffers_f64(&TriangleBufferOptions::default())?;
        if corrupt {
            b.indices = Indices::U32(vec![0, 1, 99]);
        }
        let back = Mesh::from_triangle_buffers(&b, &FromBuffersOptions::default())?;
        back.validate()?;
        Ok(back.face_count())
    }
    let cube = shapes::cube();
    assert_eq!(round_trip(&cube, false).unwrap(), 12);
    let err = round_trip(&cube, true).unwrap_err();
    assert!(matches!(err, meshloom::AnyError::Buffers(_)), "{err:?}");
}
