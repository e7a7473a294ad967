use super::*;
use crate::attr::{FaceAttr, HalfedgeAttr};
use crate::journal::HistoryLimits;
use crate::model::testing::{field, fingerprint};
use crate::shapes::{self, GridFaces};
use crate::{Error, HalfedgeKey};

/// A planar `n × n` quad grid with corner UVs from the linear field
/// `uv(x, y) = (0.25 x + 0.5 y + 1, −0.5 x + 0.125 y)` and a material per
/// row of quads.
fn textured_grid(n: usize) -> (Mesh, HalfedgeAttr<[f64; 2]>, FaceAttr<u32>) {
    let mut mesh = shapes::grid(n, n, GridFaces::Quads);
    let uv = mesh.add_halfedge_attr::<[f64; 2]>("uv").unwrap();
    let material = mesh.add_face_attr::<u32>("material").unwrap();
    let hs: Vec<HalfedgeKey> = mesh.halfedges().collect();
    for h in hs {
        let view = mesh.halfedge(h).unwrap();
        if view.is_boundary() {
            continue;
        }
        let p = view.origin().position().unwrap();
        mesh.set_attr(&uv, h, field(p)).unwrap();
    }
    let fs: Vec<FaceKey> = mesh.faces().collect();
    for f in fs {
        let c = face_centre(&mesh, f);
        mesh.set_attr(&material, f, (c[1] * 10.0) as u32).unwrap();
    }
    (mesh, uv, material)
}

fn face_centre(mesh: &Mesh, f: FaceKey) -> V3 {
    let vs: Vec<V3> = mesh
        .face(f)
        .unwrap()
        .vertices()
        .map(|v| mesh.position(v).unwrap())
        .collect();
    let n = vs.len() as f64;
    std::array::from_fn(|k| vs.iter().map(|p| p[k]).sum::<f64>() / n)
}

/// An inner edge of `mesh` along x.
fn edge_along_x(mesh: &Mesh) -> EdgeKey {
    mesh.edges()
        .find(|&e| {
            let [a, b] = mesh.edge(e).unwrap().vertices();
            let (p, q) = (mesh.position(a).unwrap(), mesh.position(b).unwrap());
            (p[1] - q[1]).abs() < 1e-12 && !mesh.edge(e).unwrap().is_boundary()
        })
        .unwrap()
}

#[test]
fn cuts_across_a_grid_add_the_expected_elements_and_keep_a_linear_uv_field() {
    for (n, cuts, factor) in [(4, 1, 0.5), (5, 3, 0.3), (3, 2, 0.8)] {
        let (mut mesh, uv, material) = textured_grid(n);
        let (v0, e0, f0) = (mesh.vertex_count(), mesh.edge_count(), mesh.face_count());
        let e = edge_along_x(&mesh);
        let materials_before: Vec<u32> = {
            let mut m: Vec<u32> = mesh
                .faces()
                .map(|f| *mesh.attr(&material, f).unwrap().unwrap())
                .collect();
            m.sort();
            m.dedup();
            m
        };
        let options = LoopCutOptions {
            cuts,
            factor,
            smoothness: 0.0,
        };
        let cut = mesh.loop_cut(e, &options).unwrap();
        mesh.validate().unwrap();
        // A ring across an n × n grid: n + 1 edges, n quads.
        assert!(!cut.closed);
        assert_eq!(cut.vertices.len(), cuts * (n + 1));
        assert_eq!(cut.edges.len(), cuts * n);
        assert_eq!(mesh.vertex_count(), v0 + cuts * (n + 1));
        assert_eq!(mesh.edge_count(), e0 + cuts * (n + 1) + cuts * n);
        assert_eq!(mesh.face_count(), f0 + cuts * n);
        // The new vertices sit at the mapped parameters along their ring
        // edges (which run along x, as `e` does), counted from one end or
        // the other.
        let xs: Vec<f64> = cut.vertices[..cuts]
            .iter()
            .map(|&v| mesh.position(v).unwrap()[0])
            .collect();
        let ts = cut_parameters(cuts, factor);
        for (x, t) in xs.iter().zip(&ts) {
            let frac = x - x.floor(); // the grid's cells are 1 wide
            assert!(
                (frac - t).abs() < 1e-12 || (frac - (1.0 - t)).abs() < 1e-12,
                "{x} at {t}"
            );
        }
        // Every corner still carries the field at its vertex: interpolated
        // where it should be, nothing copied across.
        for h in mesh
            .halfedges()
            .filter(|&h| !mesh.halfedge(h).unwrap().is_boundary())
        {
            let p = mesh.halfedge(h).unwrap().origin().position().unwrap();
            let got = *mesh.attr(&uv, h).unwrap().unwrap();
            let want = field(p);
            assert!((got[0] - want[0]).abs() < 1e-12 && (got[1] - want[1]).abs() < 1e-12);
        }
        // Quads split into pieces of themselves: the same materials.
        let mut after: Vec<u32> = mesh
            .faces()
            .map(|f| *mesh.attr(&material, f).unwrap().unwrap())
            .collect();
        after.sort();
        after.dedup();
        assert_eq!(after, materials_before);
    }
}

#[test]
fn a_uv_seam_across_the_ring_stays_a_seam() {
    let (mut mesh, uv, _) = textured_grid(4);
    // Shift the UVs of the faces left of x = 2 by (5, 0): the edges on
    // x = 2 become a seam.
    let hs: Vec<HalfedgeKey> = mesh.halfedges().collect();
    for h in hs {
        let view = mesh.halfedge(h).unwrap();
        if !view.is_boundary() && face_centre(&mesh, view.face().key())[0] < 2.0 {
            let p = view.origin().position().unwrap();
            let f = field(p);
            mesh.set_attr(&uv, h, [f[0] + 5.0, f[1]]).unwrap();
        }
    }
    let e = edge_along_x(&mesh);
    mesh.loop_cut(
        e,
        &LoopCutOptions {
            cuts: 2,
            ..Default::default()
        },
    )
    .unwrap();
    mesh.validate().unwrap();
    for h in mesh
        .halfedges()
        .filter(|&h| !mesh.halfedge(h).unwrap().is_boundary())
    {
        let view = mesh.halfedge(h).unwrap();
        let p = view.origin().position().unwrap();
        let left = face_centre(&mesh, view.face().key())[0] < 2.0;
        let f = field(p);
        let want = if left { [f[0] + 5.0, f[1]] } else { f };
        let got = *mesh.attr(&uv, h).unwrap().unwrap();
        assert!(
            (got[0] - want[0]).abs() < 1e-12 && (got[1] - want[1]).abs() < 1e-12,
            "{p:?}"
        );
    }
}

#[test]
fn a_closed_ring_cuts_closed_loops_and_keeps_the_topology() {
    let mut mesh = shapes::torus(12, 6, 1.0, 0.3).unwrap();
    let chi = mesh.euler_characteristic();
    let e = mesh.edges().next().unwrap();
    let ring = mesh.edge_ring(e).unwrap();
    assert!(ring.closed);
    let cut = mesh
        .loop_cut(
            e,
            &LoopCutOptions {
                cuts: 3,
                ..Default::default()
            },
        )
        .unwrap();
    mesh.validate().unwrap();
    assert!(cut.closed);
    assert_eq!(cut.vertices.len(), 3 * ring.keys.len());
    assert_eq!(cut.edges.len(), 3 * ring.keys.len());
    assert_eq!(mesh.euler_characteristic(), chi);
    // Each new loop is an edge loop of the result, closed.
    let run = mesh.edge_loop(cut.edges[0]).unwrap();
    assert!(run.closed && run.keys.len() == ring.keys.len());
}

#[test]
fn smoothness_moves_the_cut_towards_the_surface_and_zero_keeps_it_on_the_edge() {
    // A UV sphere's meridian ring edges are chords: a smooth cut bulges
    // outwards, closer to the unit sphere than the chords' midpoints.
    let radius = |mesh: &Mesh, vs: &[VertexKey]| -> f64 {
        vs.iter()
            .map(|&v| vec3::norm(mesh.position(v).unwrap()))
            .sum::<f64>()
            / vs.len() as f64
    };
    let sphere = shapes::uv_sphere(12, 6);
    let e = sphere
        .edges()
        .find(|&e| {
            sphere.edge_ring(e).unwrap().closed && sphere.edge_ring(e).unwrap().keys.len() == 12
        })
        .unwrap();
    let mut flat = sphere.clone();
    let linear = flat.loop_cut(e, &LoopCutOptions::default()).unwrap();
    let mut round = sphere.clone();
    let smooth = round
        .loop_cut(
            e,
            &LoopCutOptions {
                smoothness: 1.0,
                ..Default::default()
            },
        )
        .unwrap();
    round.validate().unwrap();
    let (r0, r1) = (
        radius(&flat, &linear.vertices),
        radius(&round, &smooth.vertices),
    );
    assert!(
        r0 < 0.99 && (r1 - 1.0).abs() < (r0 - 1.0).abs() / 4.0,
        "{r0} {r1}"
    );
    // On a plane the surface curve is the edge itself.
    let (mut grid, _, _) = textured_grid(3);
    let e = edge_along_x(&grid);
    let cut = grid
        .loop_cut(
            e,
            &LoopCutOptions {
                smoothness: 1.0,
                ..Default::default()
            },
        )
        .unwrap();
    for v in cut.vertices {
        let p = grid.position(v).unwrap();
        assert!(p[2] == 0.0 && ((p[0] * 2.0).fract()).abs() < 1e-12, "{p:?}");
    }
}

#[test]
fn refusals_change_nothing_and_a_cut_is_one_undo_step() {
    let (mut mesh, _, _) = textured_grid(3);
    mesh.history_mut().enable(HistoryLimits::default());
    let before = fingerprint(&mesh);
    let e = edge_along_x(&mesh);
    let bad = [
        LoopCutOptions {
            cuts: 0,
            ..Default::default()
        },
        LoopCutOptions {
            cuts: MAX_CUTS + 1,
            ..Default::default()
        },
        LoopCutOptions {
            factor: 0.0,
            ..Default::default()
        },
        LoopCutOptions {
            factor: 1.0,
            ..Default::default()
        },
        LoopCutOptions {
            factor: f64::NAN,
            ..Default::default()
        },
        LoopCutOptions {
            smoothness: f64::INFINITY,
            ..Default::default()
        },
    ];
    for o in bad {
        let err = mesh.loop_cut(e, &o).unwrap_err();
        assert!(
            matches!(
                err,
                Error::Refused {
                    reason: Refusal::Parameter(_),
                    ..
                }
            ),
            "{err:?}"
        );
        assert!(mesh.check_loop_cut(e, &o).is_err());
        assert_eq!(fingerprint(&mesh), before);
    }
    let undo = mesh.history().undo_len();
    mesh.loop_cut(
        e,
        &LoopCutOptions {
            cuts: 4,
            factor: 0.25,
            smoothness: 0.5,
        },
    )
    .unwrap();
    assert_eq!(mesh.history().undo_len(), undo + 1);
    assert_ne!(fingerprint(&mesh), before);
    assert!(mesh.undo());
    assert_eq!(fingerprint(&mesh), before);
    // Triangles: no quad beside the edge.
    let mut tris = shapes::grid(3, 3, GridFaces::Triangles);
    let e = tris.edges().next().unwrap();
    let err = tris.loop_cut(e, &LoopCutOptions::default()).unwrap_err();
    assert!(
        matches!(
            err,
            Error::Refused {
                reason: Refusal::NotQuads,
                ..
            }
        ),
        "{err:?}"
    );
    // A stale edge.
    let f = mesh.faces().next().unwrap();
    let gone: Vec<EdgeKey> = mesh.face(f).unwrap().edges().collect();
    mesh.remove_face(f).unwrap();
    if let Some(&e) = gone.iter().find(|&&e| mesh.edge(e).is_err()) {
        assert!(matches!(
            mesh.loop_cut(e, &LoopCutOptions::default()),
            Err(Error::StaleKey { .. })
        ));
    }
}

#[test]
fn ring_ends_at_other_faces_gain_corners_and_every_edge_of_a_mixed_mesh_cuts_or_refuses() {
    // A quad strip ending in a triangle fan on both sides: the ring stops
    // at the triangles, which gain the cut vertices as corners.
    let sphere = shapes::uv_sphere(8, 5);
    for e in sphere.edges() {
        let mut m = sphere.clone();
        let before = fingerprint(&m);
        match m.loop_cut(
            e,
            &LoopCutOptions {
                cuts: 2,
                factor: 0.4,
                smoothness: 0.0,
            },
        ) {
            Ok(cut) => {
                m.validate().unwrap();
                assert_eq!(m.vertex_count(), sphere.vertex_count() + cut.vertices.len());
                assert_eq!(m.face_count(), sphere.face_count() + cut.edges.len());
                assert_eq!(m.euler_characteristic(), 2);
            }
            Err(err) => {
                assert!(
                    matches!(
                        err,
                        Error::Refused {
                            reason: Refusal::NotQuads | Refusal::Crossing,
                            ..
                        }
                    ),
                    "{err:?}"
                );
                assert_eq!(fingerprint(&m), before);
            }
        }
    }
}
