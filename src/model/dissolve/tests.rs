use super::*;
use crate::attr::{Attr, Conserved, FaceAttr, HalfedgeAttr};

type Mass = Attr<FaceKey, f64, Conserved>;
use crate::journal::HistoryLimits;
use crate::model::testing::{field, fingerprint, mixed_meshes, next_random, random_faces};
use crate::shapes::{self, GridFaces};
use crate::vec3::V3;
use crate::{Error, HalfedgeKey};

/// A planar `n × n` quad grid with corner UVs from [`field`], shifted by 10
/// in u right of `x = seam` (a UV seam along that line), a material per
/// column of quads (`x` of the centre, floored) and a conserved mass per
/// face (its index + 1).
fn textured_grid(n: usize, seam: f64) -> (Mesh, HalfedgeAttr<[f64; 2]>, FaceAttr<u32>, Mass) {
    let mut mesh = shapes::grid(n, n, GridFaces::Quads);
    let uv = mesh.add_halfedge_attr::<[f64; 2]>("uv").unwrap();
    let material = mesh.add_face_attr::<u32>("material").unwrap();
    let mass = mesh
        .add_attr_with_rule::<FaceKey, f64, Conserved>("mass")
        .unwrap();
    let fs: Vec<FaceKey> = mesh.faces().collect();
    for (i, &f) in fs.iter().enumerate() {
        let c = centre(&mesh, f);
        mesh.set_attr(&material, f, c[0] as u32).unwrap();
        mesh.set_attr(&mass, f, i as f64 + 1.0).unwrap();
        let hs: Vec<HalfedgeKey> = mesh.face(f).unwrap().halfedges().collect();
        for h in hs {
            let p = mesh.halfedge(h).unwrap().origin().position().unwrap();
            mesh.set_attr(&uv, h, island_uv(p, c[0] > seam)).unwrap();
        }
    }
    (mesh, uv, material, mass)
}

fn island_uv(p: V3, right: bool) -> [f64; 2] {
    let [u, v] = field(p);
    [u + if right { 10.0 } else { 0.0 }, v]
}

fn centre(mesh: &Mesh, f: FaceKey) -> V3 {
    let vs: Vec<V3> = mesh
        .face(f)
        .unwrap()
        .vertices()
        .map(|v| mesh.position(v).unwrap())
        .collect();
    let n = vs.len() as f64;
    std::array::from_fn(|k| vs.iter().map(|p| p[k]).sum::<f64>() / n)
}

/// The faces whose centre lies in `[x0, x1] × [y0, y1]`.
fn faces_in(mesh: &Mesh, x: [f64; 2], y: [f64; 2]) -> Vec<FaceKey> {
    mesh.faces()
        .filter(|&f| {
            let c = centre(mesh, f);
            c[0] > x[0] && c[0] < x[1] && c[1] > y[0] && c[1] < y[1]
        })
        .collect()
}

fn total(mesh: &Mesh, mass: &Mass) -> f64 {
    mesh.faces()
        .filter_map(|f| mesh.attr(mass, f).unwrap().copied())
        .sum()
}

fn counts(mesh: &Mesh) -> [usize; 3] {
    [mesh.vertex_count(), mesh.edge_count(), mesh.face_count()]
}

/// Every corner of every face still holds its island's field value.
fn uvs_hold(mesh: &Mesh, uv: &HalfedgeAttr<[f64; 2]>, seam: f64) {
    for f in mesh.faces() {
        let right = centre(mesh, f)[0] > seam;
        for h in mesh.face(f).unwrap().halfedges() {
            let p = mesh.halfedge(h).unwrap().origin().position().unwrap();
            let want = island_uv(p, right);
            let got = *mesh.attr(uv, h).unwrap().unwrap();
            assert!((got[0] - want[0]).abs() < 1e-12 && (got[1] - want[1]).abs() < 1e-12);
        }
    }
}

#[test]
fn a_3x3_patch_of_a_grid_becomes_one_face_with_its_values() {
    let (mut mesh, uv, material, mass) = textured_grid(5, 100.0);
    let before = total(&mesh, &mass);
    // The patch in columns 1..4 and rows 1..4: 9 quads, 12 inner edges,
    // 4 inner vertices; columns 1, 2, 3 have materials 1, 2, 3.
    let patch = faces_in(&mesh, [1.0, 4.0], [1.0, 4.0]);
    assert_eq!(patch.len(), 9);
    assert_eq!(counts(&mesh), [36, 60, 25]);
    let d = mesh.dissolve_faces(&patch).unwrap();
    mesh.validate().unwrap();
    assert_eq!(counts(&mesh), [32, 48, 17]);
    assert_eq!(d.faces, vec![patch[0]]);
    assert_eq!(
        (d.removed_vertices, d.removed_edges, d.removed_faces),
        (4, 12, 8)
    );
    assert_eq!(mesh.face(patch[0]).unwrap().degree(), 12);
    // Conserved: the total is kept; incompatible: the columns disagreed.
    assert!((total(&mesh, &mass) - before).abs() < 1e-9);
    assert_eq!(mesh.attr(&material, patch[0]).unwrap(), None);
    uvs_hold(&mesh, &uv, 100.0);
    // One column of the patch (one material) keeps its material.
    let (mut mesh, _, material, _) = textured_grid(5, 100.0);
    let column = faces_in(&mesh, [2.0, 3.0], [1.0, 4.0]);
    let d = mesh.dissolve_faces(&column).unwrap();
    assert_eq!(mesh.attr(&material, d.faces[0]).unwrap(), Some(&2));
}

#[test]
fn a_ring_of_faces_or_faces_meeting_at_a_vertex_are_refused_unchanged() {
    let (mut mesh, ..) = textured_grid(5, 100.0);
    mesh.history_mut().enable(HistoryLimits::default());
    let before = fingerprint(&mesh);
    let patch = faces_in(&mesh, [1.0, 4.0], [1.0, 4.0]);
    let ring: Vec<FaceKey> = patch
        .iter()
        .copied()
        .filter(|&f| centre(&mesh, f)[..2] != [2.5, 2.5])
        .collect();
    assert_eq!(ring.len(), 8);
    // Faces (x, y) = (0,0) (0,1) (0,2) (1,2) (2,2) (2,1) and (1,0): (1,0)
    // and (2,1) meet at the vertex (2, 1) only.
    let pinched: Vec<FaceKey> = [[0, 0], [0, 1], [0, 2], [1, 2], [2, 2], [2, 1], [1, 0]]
        .iter()
        .map(|&[x, y]| {
            faces_in(
                &mesh,
                [x as f64, x as f64 + 1.0],
                [y as f64, y as f64 + 1.0],
            )[0]
        })
        .collect();
    for faces in [ring, pinched] {
        let err = mesh.dissolve_faces(&faces).unwrap_err();
        assert!(
            matches!(
                err,
                Error::Refused {
                    reason: Refusal::NonManifold,
                    ..
                }
            ),
            "{err:?}"
        );
        assert!(mesh.check_dissolve_faces(&faces).is_err());
        assert_eq!(fingerprint(&mesh), before);
    }
    let hole = mesh.holes().next().unwrap();
    assert!(mesh.dissolve_faces(&[hole]).is_err());
    assert!(mesh.dissolve_faces(&[]).is_err());
    assert!(mesh.dissolve_vertices(&[]).is_err());
    assert!(mesh
        .dissolve_edges(&[], &DissolveEdgesOptions::default())
        .is_err());
    assert_eq!(fingerprint(&mesh), before);
    // A closed surface whole is refused too (no boundary loop left).
    let mut cube = shapes::cube();
    let all: Vec<FaceKey> = cube.faces().collect();
    assert!(cube.dissolve_faces(&all).is_err());
}

#[test]
fn dissolving_an_edge_ring_merges_a_row_and_joins_the_boundary_vertices() {
    let (mut mesh, uv, _, mass) = textured_grid(4, 100.0);
    let before = total(&mesh, &mass);
    // The vertical inner edges of the bottom row of quads.
    let ring: Vec<EdgeKey> = mesh
        .edges()
        .filter(|&e| {
            let [a, b] = mesh.edge(e).unwrap().vertices();
            let (p, q) = (mesh.position(a).unwrap(), mesh.position(b).unwrap());
            p[0] == q[0] && p[0] > 0.0 && p[0] < 4.0 && p[1].max(q[1]) == 1.0
        })
        .collect();
    assert_eq!(ring.len(), 3);
    let mut plain = mesh.clone();
    let d = plain
        .dissolve_edges(&ring, &DissolveEdgesOptions { vertices: false })
        .unwrap();
    plain.validate().unwrap();
    assert_eq!(counts(&plain), [25, 37, 13]);
    assert_eq!(plain.face(d.faces[0]).unwrap().degree(), 10);
    // With the vertices: the three on the bottom boundary are left with
    // two edges and go; the three above keep three edges.
    let d = mesh
        .dissolve_edges(&ring, &DissolveEdgesOptions::default())
        .unwrap();
    mesh.validate().unwrap();
    assert_eq!(counts(&mesh), [22, 34, 13]);
    assert_eq!(mesh.face(d.faces[0]).unwrap().degree(), 7);
    assert_eq!(d.edges.len(), 1);
    assert!((total(&mesh, &mass) - before).abs() < 1e-9);
    uvs_hold(&mesh, &uv, 100.0);
    // A boundary edge has no face beyond: skipped, nothing changes.
    let edge = mesh
        .edges()
        .find(|&e| mesh.edge(e).unwrap().is_boundary())
        .unwrap();
    let before = fingerprint(&mesh);
    let d = mesh
        .dissolve_edges(&[edge], &DissolveEdgesOptions::default())
        .unwrap();
    assert!(d.faces.is_empty());
    assert_eq!(fingerprint(&mesh), before);
}

#[test]
fn a_closed_edge_ring_would_make_an_annulus_and_is_refused() {
    let mut torus = shapes::torus(7, 4, 1.0, 0.3).unwrap();
    let e = torus.edges().next().unwrap();
    let ring = torus.edge_ring(e).unwrap();
    assert!(ring.closed);
    let before = fingerprint(&torus);
    let err = torus
        .dissolve_edges(&ring.keys, &DissolveEdgesOptions::default())
        .unwrap_err();
    assert!(
        matches!(
            err,
            Error::Refused {
                reason: Refusal::NonManifold,
                ..
            }
        ),
        "{err:?}"
    );
    assert_eq!(fingerprint(&torus), before);
    // All but one edge of it: the strip's loop would meet the last edge's
    // ends twice. Half of it: one long face of m + 1 quads.
    assert!(torus
        .check_dissolve_edges(&ring.keys[1..], &DissolveEdgesOptions::default())
        .is_err());
    let m = ring.keys.len() / 2;
    let d = torus
        .dissolve_edges(&ring.keys[..m], &DissolveEdgesOptions::default())
        .unwrap();
    torus.validate().unwrap();
    assert_eq!(torus.face(d.faces[0]).unwrap().degree(), 2 * m + 4);
}

#[test]
fn dissolving_vertices_merges_their_faces_and_joins_chains() {
    let (mut mesh, uv, material, mass) = textured_grid(4, 1.5);
    let before = total(&mesh, &mass);
    let at = |mesh: &Mesh, x: f64, y: f64| {
        mesh.vertices()
            .find(|&v| mesh.position(v).unwrap()[..2] == [x, y])
            .unwrap()
    };
    // An inner vertex on the seam and the material border (x = 2, y = 2),
    // and a boundary vertex (2, 0) of three edges.
    let (inner, side) = (at(&mesh, 2.0, 2.0), at(&mesh, 2.0, 0.0));
    let d = mesh.dissolve_vertices(&[inner, side]).unwrap();
    mesh.validate().unwrap();
    // Four quads around (2, 2), two around (2, 0), sharing none: 2 faces
    // from 6; (2, 0) then joins its two boundary edges.
    assert_eq!(d.faces.len(), 2);
    assert_eq!(counts(&mesh), [23, 40 - 4 - 1 - 1, 12]);
    assert!(mesh.vertex(inner).is_err() && mesh.vertex(side).is_err());
    assert_eq!(mesh.face(d.faces[0]).unwrap().degree(), 8);
    assert_eq!(mesh.face(d.faces[1]).unwrap().degree(), 5);
    assert_eq!(mesh.attr(&material, d.faces[0]).unwrap(), None);
    assert!((total(&mesh, &mass) - before).abs() < 1e-9);
    // Corners keep their values: each still fits the field of its island
    // (the merged faces straddle the seam: check corner by corner).
    for f in &d.faces {
        for h in mesh.face(*f).unwrap().halfedges() {
            let view = mesh.halfedge(h).unwrap();
            let p = view.origin().position().unwrap();
            let got = *mesh.attr(&uv, h).unwrap().unwrap();
            assert!(got == island_uv(p, false) || got == island_uv(p, true));
        }
    }
    // A grid corner of triangles: removing it leaves two sides.
    let mut tris = shapes::grid(2, 2, GridFaces::Triangles);
    let corner = tris
        .vertices()
        .find(|&v| tris.vertex(v).unwrap().outgoing().count() == 2)
        .unwrap();
    let before = fingerprint(&tris);
    let err = tris.dissolve_vertices(&[corner]).unwrap_err();
    assert!(
        matches!(
            err,
            Error::Refused {
                reason: Refusal::Degenerate,
                ..
            }
        ),
        "{err:?}"
    );
    assert_eq!(fingerprint(&tris), before);
}

#[test]
fn a_dissolve_is_one_undo_step() {
    let (mut mesh, ..) = textured_grid(4, 1.5);
    mesh.history_mut().enable(HistoryLimits::default());
    let before = fingerprint(&mesh);
    let undo = mesh.history().undo_len();
    let patch = faces_in(&mesh, [0.0, 3.0], [0.0, 2.0]);
    mesh.dissolve_faces(&patch).unwrap();
    let v = mesh
        .vertices()
        .find(|&v| !mesh.vertex(v).unwrap().is_boundary())
        .unwrap();
    mesh.dissolve_vertices(&[v]).unwrap();
    assert_eq!(mesh.history().undo_len(), undo + 2);
    assert!(mesh.undo() && mesh.undo());
    assert_eq!(fingerprint(&mesh), before);
}

#[test]
fn random_selections_dissolve_and_validate_or_refuse_unchanged() {
    let mut seed = 0x2545_f491_4f6c_dd1d_u64;
    let (mut done, mut refused) = (0, 0);
    for mesh in mixed_meshes() {
        for round in 0..24 {
            let mut m = mesh.clone();
            let mass = m
                .add_attr_with_rule::<FaceKey, f64, Conserved>("mass")
                .unwrap();
            for (i, f) in m.faces().collect::<Vec<_>>().into_iter().enumerate() {
                m.set_attr(&mass, f, 1.0 + i as f64).unwrap();
            }
            let total0 = total(&m, &mass);
            let before = fingerprint(&m);
            let r = match round % 3 {
                0 => {
                    let fs = random_faces(&m, &mut seed);
                    m.dissolve_faces(&fs)
                }
                1 => {
                    let es: Vec<EdgeKey> = m
                        .edges()
                        .filter(|_| next_random(&mut seed) % 4 == 0)
                        .collect();
                    let vertices = next_random(&mut seed) % 2 == 0;
                    m.dissolve_edges(&es, &DissolveEdgesOptions { vertices })
                }
                _ => {
                    let vs: Vec<VertexKey> = m
                        .vertices()
                        .filter(|_| next_random(&mut seed) % 6 == 0)
                        .collect();
                    m.dissolve_vertices(&vs)
                }
            };
            match r {
                Ok(_) => {
                    m.validate().unwrap();
                    assert!((total(&m, &mass) - total0).abs() < 1e-6 * total0);
                    done += 1;
                }
                Err(Error::Refused { .. }) => {
                    assert_eq!(fingerprint(&m), before);
                    refused += 1;
                }
                Err(e) => panic!("{e:?}"),
            }
        }
    }
    assert!(done > 10 && refused > 0, "{done} done, {refused} refused");
}
