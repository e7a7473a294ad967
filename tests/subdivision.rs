//! Subdivision: counts, topology, stencils, convergence, attributes,
//! cancellation.

mod common;

use common::{add_totals, face_total, mesh_path, read_off, snapshot};
use meshloom::algo::{
    catmull_clark, loop_subdivide, Boundary, Flow, Progress, SubdivisionOptions, SubdivisionReport,
    VertexInterpolation,
};
use meshloom::attr::Value;
use meshloom::{EdgeKey, FaceKey, Mesh, VertexKey};

type Scheme =
    fn(&mut Mesh, &SubdivisionOptions, Progress<'_>) -> meshloom::Result<SubdivisionReport>;

fn counts(m: &Mesh) -> (usize, usize, usize, usize) {
    (
        m.vertex_count(),
        m.edge_count(),
        m.face_count(),
        m.hole_count(),
    )
}

fn add(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

fn scale(a: [f64; 3], k: f64) -> [f64; 3] {
    [a[0] * k, a[1] * k, a[2] * k]
}

fn close(a: [f64; 3], b: [f64; 3]) -> bool {
    (0..3).all(|i| (a[i] - b[i]).abs() < 1e-12)
}

fn mean(ps: &[[f64; 3]]) -> [f64; 3] {
    scale(
        ps.iter().fold([0.0; 3], |s, &p| add(s, p)),
        1.0 / ps.len() as f64,
    )
}

/// The mean of face `f`'s corner positions.
fn centroid(m: &Mesh, f: FaceKey) -> [f64; 3] {
    let ps: Vec<_> = m
        .face(f)
        .unwrap()
        .vertices()
        .map(|u| m.position(u).unwrap())
        .collect();
    mean(&ps)
}

/// The new vertex on old edge `a`–`b`: the one vertex next to both that
/// is not an old vertex.
fn edge_point(m: &Mesh, old: &[VertexKey], a: VertexKey, b: VertexKey) -> VertexKey {
    let nb: Vec<VertexKey> = m.vertex(b).unwrap().neighbors().collect();
    let common: Vec<VertexKey> = m
        .vertex(a)
        .unwrap()
        .neighbors()
        .filter(|v| nb.contains(v) && !old.contains(v))
        .collect();
    assert_eq!(common.len(), 1, "edge point of {a:?}-{b:?}");
    common[0]
}

fn edge_between(m: &Mesh, a: VertexKey, b: VertexKey) -> EdgeKey {
    let h = m.find_halfedge(a, b).unwrap().expect("edge");
    m.halfedge(h).unwrap().edge().key()
}

/// The old edges as vertex pairs, and for each the centroids of the faces
/// beside it and its opposite corners (for triangles).
struct OldEdge {
    a: VertexKey,
    b: VertexKey,
    face_centroids: Vec<[f64; 3]>,
    opposite: Vec<VertexKey>,
}

fn old_edges(m: &Mesh) -> Vec<OldEdge> {
    m.edges()
        .map(|e| {
            let ev = m.edge(e).unwrap();
            let [a, b] = ev.vertices();
            let mut face_centroids = Vec::new();
            let mut opposite = Vec::new();
            for f in ev.faces().into_iter().flatten() {
                let vs: Vec<VertexKey> = m.face(f).unwrap().vertices().collect();
                let ps: Vec<[f64; 3]> = vs.iter().map(|&v| m.position(v).unwrap()).collect();
                face_centroids.push(mean(&ps));
                opposite.extend(vs.into_iter().filter(|&v| v != a && v != b));
            }
            OldEdge {
                a,
                b,
                face_centroids,
                opposite,
            }
        })
        .collect()
}

// ----- counts and topology ------------------------------------------------

#[test]
fn loop_counts_on_shapes() {
    for mut mesh in [
        meshloom::shapes::tetrahedron(),
        meshloom::shapes::icosahedron(),
        meshloom::shapes::icosphere(2),
        meshloom::shapes::grid(4, 3, meshloom::shapes::GridFaces::Triangles),
    ] {
        for _ in 0..2 {
            let (v, e, f, h) = counts(&mesh);
            let r = loop_subdivide(&mut mesh, &SubdivisionOptions::default(), Progress::none())
                .unwrap();
            assert_eq!(counts(&mesh), (v + e, 2 * e + 3 * f, 4 * f, h));
            assert_eq!(r.output.faces, 4 * f);
            mesh.validate().unwrap();
        }
    }
}

#[test]
fn catmull_clark_counts_on_shapes() {
    for mut mesh in [
        meshloom::shapes::tetrahedron(),
        meshloom::shapes::cube(),
        meshloom::shapes::icosphere(1),
        meshloom::shapes::grid(4, 3, meshloom::shapes::GridFaces::Quads),
        meshloom::shapes::disk(7),
    ] {
        for _ in 0..2 {
            let (v, e, f, h) = counts(&mesh);
            let corners: usize = mesh.faces().map(|f| mesh.face(f).unwrap().degree()).sum();
            catmull_clark(&mut mesh, &SubdivisionOptions::default(), Progress::none()).unwrap();
            assert_eq!(counts(&mesh), (v + e + f, 2 * e + corners, corners, h));
            mesh.validate().unwrap();
        }
    }
}

#[test]
fn report_counts_every_level() {
    let mut mesh = meshloom::shapes::cube();
    let r = catmull_clark(
        &mut mesh,
        &SubdivisionOptions::default().levels(3),
        Progress::none(),
    )
    .unwrap();
    assert_eq!(r.input.faces, 6);
    let faces: Vec<usize> = r.levels.iter().map(|l| l.output.faces).collect();
    assert_eq!(faces, [24, 96, 384]);
    assert_eq!(r.output.vertices, mesh.vertex_count());
    let r = catmull_clark(
        &mut mesh,
        &SubdivisionOptions::default().levels(0),
        Progress::none(),
    )
    .unwrap();
    assert!(r.levels.is_empty());
    assert_eq!(mesh.face_count(), 384);
}

fn topology(m: &Mesh) -> (Option<u64>, usize, usize) {
    let s = m.stats();
    (s.genus, s.components, s.holes)
}

/// Genus, components and holes are kept; every level validates; the
/// counts follow the formulas.
#[test]
fn real_meshes_keep_their_topology() {
    let files = [
        "closed/cgal_cube.off",
        "closed/cgal_tetrahedron.off",
        "closed/cgal_icosahedron.off",
        "closed/cgal_sphere966.off",
        "closed/openmesh_sphere840.ply",
        "boundary/cgal_mesh_with_border.off",
        "boundary/cgal_open_cube.off",
        "boundary/cgal_quads_to_stitch.off",
        "boundary/cgal_triangular_hole.off",
        "polygons/cgal_3torus.off",
        "polygons/cgal_P.off",
        "polygons/cgal_corner_with_hole.off",
        "polygons/cgal_cube_poly.off",
        "polygons/cgal_torus_quad.off",
        "polygons/geomview_dodec.off",
        "polygons/compas_hypar.obj",
        "polygons/compas_quadmesh.obj",
    ];
    let mut loops = 0;
    for file in files {
        let original = read_off(&mesh_path(file));
        let before = topology(&original);
        let mut mesh = original.clone();
        for level in 0..2 {
            let (v, e, f, h) = counts(&mesh);
            let corners: usize = mesh.faces().map(|f| mesh.face(f).unwrap().degree()).sum();
            catmull_clark(&mut mesh, &SubdivisionOptions::default(), Progress::none())
                .unwrap_or_else(|err| panic!("{file}: {err}"));
            assert_eq!(
                counts(&mesh),
                (v + e + f, 2 * e + corners, corners, h),
                "{file}"
            );
            mesh.validate()
                .unwrap_or_else(|err| panic!("{file} level {level}: {err}"));
            assert_eq!(topology(&mesh), before, "{file}");
        }
        if original
            .faces()
            .all(|f| original.face(f).unwrap().degree() == 3)
        {
            loops += 1;
            let mut mesh = original.clone();
            for _ in 0..2 {
                let (v, e, f, h) = counts(&mesh);
                loop_subdivide(&mut mesh, &SubdivisionOptions::default(), Progress::none())
                    .unwrap_or_else(|err| panic!("{file}: {err}"));
                assert_eq!(counts(&mesh), (v + e, 2 * e + 3 * f, 4 * f, h), "{file}");
                mesh.validate().unwrap();
                assert_eq!(topology(&mesh), before, "{file}");
            }
        } else {
            // Loop refuses polygons and leaves the mesh as it was.
            let mut mesh = original.clone();
            let snap = snapshot(&mesh);
            let err = loop_subdivide(&mut mesh, &SubdivisionOptions::default(), Progress::none())
                .unwrap_err();
            assert!(
                matches!(err, meshloom::Error::Unsuitable { .. }),
                "{file}: {err}"
            );
            assert_eq!(snapshot(&mesh), snap);
        }
    }
    assert!(loops >= 6, "Loop ran on {loops} meshes");
}

// ----- stencils -------------------------------------------------------------

/// Loop on a tetrahedron: valence 3, β = 3/16 (worked by hand:
/// (5/8 − (3/8 + ¼ cos 120°)²)/3); edge points ⅜ (a + b) + ⅛ (c + d).
#[test]
fn loop_stencils_on_a_tetrahedron() {
    let mut m = meshloom::shapes::tetrahedron();
    let old: Vec<VertexKey> = m.vertices().collect();
    let p: Vec<[f64; 3]> = old.iter().map(|&v| m.position(v).unwrap()).collect();
    let edges = old_edges(&m);
    loop_subdivide(&mut m, &SubdivisionOptions::default(), Progress::none()).unwrap();
    let beta = 3.0 / 16.0;
    for (i, &v) in old.iter().enumerate() {
        let others = (0..4)
            .filter(|&j| j != i)
            .fold([0.0; 3], |s, j| add(s, p[j]));
        let expected = add(scale(p[i], 1.0 - 3.0 * beta), scale(others, beta));
        assert!(close(m.position(v).unwrap(), expected), "vertex {i}");
    }
    for e in &edges {
        let pos = |v: VertexKey| p[old.iter().position(|&o| o == v).unwrap()];
        let expected = add(
            scale(add(pos(e.a), pos(e.b)), 0.375),
            scale(add(pos(e.opposite[0]), pos(e.opposite[1])), 0.125),
        );
        let mid = edge_point(&m, &old, e.a, e.b);
        assert!(close(m.position(mid).unwrap(), expected));
    }
}

/// Catmull-Clark on a cube, checked with the (F + 2R + (n − 3) P)/n form
/// of the vertex rule (F: mean of the face points, R: mean of the edge
/// midpoints), edge points (a + b + F₁ + F₂)/4 and centroids.
#[test]
fn catmull_clark_stencils_on_a_cube() {
    let mut m = meshloom::shapes::cube();
    let old: Vec<VertexKey> = m.vertices().collect();
    let p: Vec<[f64; 3]> = old.iter().map(|&v| m.position(v).unwrap()).collect();
    let centroids: Vec<[f64; 3]> = m.faces().map(|f| centroid(&m, f)).collect();
    let expected_vertex: Vec<[f64; 3]> = old
        .iter()
        .enumerate()
        .map(|(i, &v)| {
            let view = m.vertex(v).unwrap();
            let n = view.degree() as f64;
            let fs: Vec<_> = view.faces().map(|f| centroid(&m, f)).collect();
            let rs: Vec<_> = view
                .neighbors()
                .map(|u| scale(add(p[i], m.position(u).unwrap()), 0.5))
                .collect();
            scale(
                add(add(mean(&fs), scale(mean(&rs), 2.0)), scale(p[i], n - 3.0)),
                1.0 / n,
            )
        })
        .collect();
    let edges = old_edges(&m);
    catmull_clark(&mut m, &SubdivisionOptions::default(), Progress::none()).unwrap();
    for (i, &v) in old.iter().enumerate() {
        assert!(
            close(m.position(v).unwrap(), expected_vertex[i]),
            "vertex {i}"
        );
    }
    let mut edge_points = Vec::new();
    for e in &edges {
        let pos = |v: VertexKey| p[old.iter().position(|&o| o == v).unwrap()];
        let expected = scale(
            add(
                add(pos(e.a), pos(e.b)),
                add(e.face_centroids[0], e.face_centroids[1]),
            ),
            0.25,
        );
        let mid = edge_point(&m, &old, e.a, e.b);
        edge_points.push(mid);
        assert!(close(m.position(mid).unwrap(), expected));
    }
    // The rest are the face points, one per centroid.
    let face_points: Vec<[f64; 3]> = m
        .vertices()
        .filter(|v| !old.contains(v) && !edge_points.contains(v))
        .map(|v| m.position(v).unwrap())
        .collect();
    assert_eq!(face_points.len(), 6);
    for c in &centroids {
        assert_eq!(face_points.iter().filter(|&&q| close(q, *c)).count(), 1);
    }
}

/// A noisy icosphere with poked faces (valences 3 to 8), three faces
/// removed (holes) and two edges collapsed (dead vertex, edge and face
/// slots, not compacted).
fn irregular_mesh_with_holes() -> Mesh {
    let mut m = meshloom::shapes::icosphere(2);
    let vs: Vec<VertexKey> = m.vertices().collect();
    for (i, &v) in vs.iter().enumerate() {
        let p = m.position(v).unwrap();
        let k = 1.0 + 0.05 * ((i * 7919 % 101) as f64 / 101.0 - 0.5);
        m.set_position(v, scale(p, k)).unwrap();
    }
    let fs: Vec<FaceKey> = m.faces().collect();
    for &f in fs.iter().step_by(17) {
        m.poke_face(f).unwrap();
    }
    for &f in [fs[3], fs[40], fs[101]].iter() {
        m.remove_face(f).unwrap();
    }
    assert_eq!(m.hole_count(), 3);
    for &f in [fs[60], fs[150]].iter() {
        let h = m.face(f).unwrap().halfedge().key();
        m.collapse_edge(h).unwrap();
    }
    assert!(m.slot_counts()[0] > m.vertex_count());
    let valences: std::collections::BTreeSet<usize> = m
        .vertices()
        .map(|v| m.vertex(v).unwrap().degree())
        .collect();
    assert!(
        valences.contains(&3) && valences.contains(&8),
        "{valences:?}"
    );
    m
}

/// Where `scheme` must put each vertex of `m` (`interior(p, n, neighbours,
/// face centroids)`, `boundary(p, a, b)` with `a`, `b` its two boundary
/// neighbours), then run it and compare.
fn check_vertex_rules(
    mut m: Mesh,
    scheme: Scheme,
    interior: impl Fn([f64; 3], f64, &[[f64; 3]], &[[f64; 3]]) -> [f64; 3],
    boundary: impl Fn([f64; 3], [f64; 3], [f64; 3]) -> [f64; 3],
) {
    let old: Vec<VertexKey> = m.vertices().collect();
    let expected: Vec<[f64; 3]> = old
        .iter()
        .map(|&v| {
            let view = m.vertex(v).unwrap();
            let p = m.position(v).unwrap();
            if view.is_boundary() {
                let ends: Vec<[f64; 3]> = view
                    .outgoing()
                    .filter(|h| m.halfedge(*h).unwrap().edge().is_boundary())
                    .map(|h| m.position(m.halfedge(h).unwrap().dest().key()).unwrap())
                    .collect();
                assert_eq!(ends.len(), 2);
                return boundary(p, ends[0], ends[1]);
            }
            let us: Vec<_> = view.neighbors().map(|u| m.position(u).unwrap()).collect();
            let fs: Vec<_> = view.faces().map(|f| centroid(&m, f)).collect();
            interior(p, view.degree() as f64, &us, &fs)
        })
        .collect();
    scheme(&mut m, &SubdivisionOptions::default(), Progress::none()).unwrap();
    m.validate().unwrap();
    for (i, &v) in old.iter().enumerate() {
        let got = m.position(v).unwrap();
        assert!(
            close(got, expected[i]),
            "vertex {i}: {got:?} {:?}",
            expected[i]
        );
    }
}

/// The vertex rules of the three schemes on an irregular mesh with holes
/// and dead slots: Catmull-Clark's interior rule in the (F + 2R + (n − 3)
/// P)/n form, Loop's as (1 − nβ) v + β Σ u, √3's (Kobbelt) as (1 − α) v +
/// α/n Σ u with α = (4 − 2 cos(2π/n))/9. On the boundary the crease curve
/// ¾ v + ⅛ (a + b), except at √3's first level, which keeps boundary
/// vertices where they are.
#[test]
fn vertex_rules_on_an_irregular_mesh_with_holes() {
    use meshloom::algo::sqrt3_subdivide;
    let crease = |p, a, b| add(scale(p, 0.75), scale(add(a, b), 0.125));
    let sum = |us: &[[f64; 3]]| us.iter().fold([0.0; 3], |s, &u| add(s, u));
    let cc = |p, n: f64, us: &[[f64; 3]], fs: &[[f64; 3]]| {
        let rs: Vec<_> = us.iter().map(|&u| scale(add(p, u), 0.5)).collect();
        scale(
            add(add(mean(fs), scale(mean(&rs), 2.0)), scale(p, n - 3.0)),
            1.0 / n,
        )
    };
    check_vertex_rules(irregular_mesh_with_holes(), catmull_clark, cc, crease);
    let loop_rule = |p, n: f64, us: &[[f64; 3]], _: &[[f64; 3]]| {
        let c = 0.375 + 0.25 * (std::f64::consts::TAU / n).cos();
        let beta = (0.625 - c * c) / n;
        add(scale(p, 1.0 - n * beta), scale(sum(us), beta))
    };
    check_vertex_rules(
        irregular_mesh_with_holes(),
        loop_subdivide,
        loop_rule,
        crease,
    );
    let sqrt3_rule = |p, n: f64, us: &[[f64; 3]], _: &[[f64; 3]]| {
        let alpha = (4.0 - 2.0 * (std::f64::consts::TAU / n).cos()) / 9.0;
        add(scale(p, 1.0 - alpha), scale(sum(us), alpha / n))
    };
    let stay = |p, _, _| p;
    check_vertex_rules(
        irregular_mesh_with_holes(),
        sqrt3_subdivide,
        sqrt3_rule,
        stay,
    );
}

/// A row of three unit quads: every vertex is on the boundary.
fn quad_strip() -> Mesh {
    let mut p = Vec::new();
    for y in 0..2 {
        for x in 0..4 {
            p.push([f64::from(x), f64::from(y) * 1.5, 0.0]);
        }
    }
    let faces: Vec<[u32; 4]> = (0..3).map(|i| [i, i + 1, i + 5, i + 4]).collect();
    Mesh::from_polygons(&p, &faces).unwrap()
}

#[test]
fn boundary_stencils_on_an_open_quad_strip() {
    for boundary in [Boundary::Crease, Boundary::CreaseAndCorners] {
        let mut m = quad_strip();
        let old: Vec<VertexKey> = m.vertices().collect();
        let p: Vec<[f64; 3]> = old.iter().map(|&v| m.position(v).unwrap()).collect();
        let opts = SubdivisionOptions::default().boundary(boundary);
        let r = catmull_clark(&mut m, &opts, Progress::none()).unwrap();
        // Bottom row 0..4, top row 4..8; neighbours along the boundary.
        let along = |i: usize| -> (usize, usize) {
            match i {
                0 => (4, 1),
                3 => (2, 7),
                4 => (0, 5),
                7 => (6, 3),
                _ => (i - 1, i + 1),
            }
        };
        for i in 0..8 {
            let corner = matches!(i, 0 | 3 | 4 | 7);
            let (a, b) = along(i);
            let expected = if corner && boundary == Boundary::CreaseAndCorners {
                p[i]
            } else {
                add(scale(p[i], 0.75), scale(add(p[a], p[b]), 0.125))
            };
            assert!(
                close(m.position(old[i]).unwrap(), expected),
                "{boundary:?} {i}"
            );
        }
        // A boundary edge point is the midpoint; the inner edge 1-5 is
        // (a + b + F₁ + F₂)/4.
        let mid = edge_point(&m, &old, old[1], old[2]);
        assert!(close(m.position(mid).unwrap(), scale(add(p[1], p[2]), 0.5)));
        let inner = edge_point(&m, &old, old[1], old[5]);
        let (f1, f2) = (
            mean(&[p[0], p[1], p[5], p[4]]),
            mean(&[p[1], p[2], p[6], p[5]]),
        );
        let expected = scale(add(add(p[1], p[5]), add(f1, f2)), 0.25);
        assert!(close(m.position(inner).unwrap(), expected));
        let corners = if boundary == Boundary::CreaseAndCorners {
            4
        } else {
            0
        };
        assert_eq!(r.levels[0].corner_vertices, corners);
        m.validate().unwrap();
    }
}

#[test]
fn loop_boundary_vertex_and_edge() {
    let mut m = common::boundary_fan();
    let old: Vec<VertexKey> = m.vertices().collect();
    let p: Vec<[f64; 3]> = old.iter().map(|&v| m.position(v).unwrap()).collect();
    loop_subdivide(&mut m, &SubdivisionOptions::default(), Progress::none()).unwrap();
    // Centre 0 lies on the boundary between 1 and 5.
    let expected = add(scale(p[0], 0.75), scale(add(p[1], p[5]), 0.125));
    assert!(close(m.position(old[0]).unwrap(), expected));
    let mid = edge_point(&m, &old, old[0], old[1]);
    assert!(close(m.position(mid).unwrap(), scale(add(p[0], p[1]), 0.5)));
    // Interior edge 0-2: ⅜ (p0 + p2) + ⅛ (p1 + p3).
    let inner = edge_point(&m, &old, old[0], old[2]);
    let expected = add(scale(add(p[0], p[2]), 0.375), scale(add(p[1], p[3]), 0.125));
    assert!(close(m.position(inner).unwrap(), expected));
}

/// Sharpness on the four edges around the cube's top face.
fn creased_cube(sharpness: f64) -> (Mesh, Vec<VertexKey>, Vec<[f64; 3]>) {
    let mut m = meshloom::shapes::cube();
    let crease = m.add_edge_attr::<f64>("crease").unwrap();
    let old: Vec<VertexKey> = m.vertices().collect();
    let p: Vec<[f64; 3]> = old.iter().map(|&v| m.position(v).unwrap()).collect();
    let top: Vec<EdgeKey> = m
        .edges()
        .filter(|&e| {
            let [a, b] = m.edge(e).unwrap().vertices();
            m.position(a).unwrap()[2] > 0.5 && m.position(b).unwrap()[2] > 0.5
        })
        .collect();
    assert_eq!(top.len(), 4);
    for e in top {
        m.set_attr(&crease, e, sharpness).unwrap();
    }
    (m, old, p)
}

/// The smooth Catmull-Clark position of cube vertex `i` (valence 3).
fn cc_smooth_cube_vertex(m: &Mesh, v: VertexKey) -> [f64; 3] {
    let view = m.vertex(v).unwrap();
    let pv = m.position(v).unwrap();
    let fs: Vec<_> = view.faces().map(|f| centroid(m, f)).collect();
    let rs: Vec<_> = view
        .neighbors()
        .map(|u| scale(add(pv, m.position(u).unwrap()), 0.5))
        .collect();
    scale(add(mean(&fs), scale(mean(&rs), 2.0)), 1.0 / 3.0)
}

#[test]
fn catmull_clark_creases_hard_semi_sharp_and_fractional() {
    for s in [f64::INFINITY, 2.5, 1.0, 0.5] {
        let (mut m, old, p) = creased_cube(s);
        let smooth: Vec<[f64; 3]> = old.iter().map(|&v| cc_smooth_cube_vertex(&m, v)).collect();
        let edges = old_edges(&m);
        let opts = SubdivisionOptions::default().crease_column(Some("crease".into()));
        let r = catmull_clark(&mut m, &opts, Progress::none()).unwrap();
        assert_eq!(r.levels[0].sharp_edges, 4);
        let crease = m.attr_handle::<EdgeKey, f64, meshloom::attr::Interpolate>("crease");
        let crease = crease.unwrap();
        let top = |i: usize| p[i][2] > 0.5;
        for (i, &v) in old.iter().enumerate() {
            let got = m.position(v).unwrap();
            if !top(i) {
                assert!(close(got, smooth[i]), "s {s} bottom {i}");
                continue;
            }
            let ends: Vec<usize> = (0..8)
                .filter(|&j| {
                    j != i && top(j) && {
                        let d: f64 = (0..3).map(|k| (p[i][k] - p[j][k]).abs()).sum();
                        (d - 1.0).abs() < 1e-12
                    }
                })
                .collect();
            assert_eq!(ends.len(), 2);
            let crease_rule = add(scale(p[i], 0.75), scale(add(p[ends[0]], p[ends[1]]), 0.125));
            // Sharpness ≥ 1 keeps the crease rule at this level; 0.5 decays
            // to 0, so the rule blends half crease, half smooth.
            let expected = if s >= 1.0 {
                crease_rule
            } else {
                add(scale(crease_rule, s), scale(smooth[i], 1.0 - s))
            };
            assert!(close(got, expected), "s {s} top {i}: {got:?} {expected:?}");
        }
        for e in &edges {
            let (a, b) = (
                old.iter().position(|&o| o == e.a).unwrap(),
                old.iter().position(|&o| o == e.b).unwrap(),
            );
            let mid = edge_point(&m, &old, e.a, e.b);
            let midpoint = scale(add(p[a], p[b]), 0.5);
            let smooth = scale(
                add(
                    add(p[a], p[b]),
                    add(e.face_centroids[0], e.face_centroids[1]),
                ),
                0.25,
            );
            let sharp = top(a) && top(b);
            let expected = match (sharp, s >= 1.0) {
                (false, _) => smooth,
                (true, true) => midpoint,
                (true, false) => add(scale(midpoint, s), scale(smooth, 1.0 - s)),
            };
            assert!(
                close(m.position(mid).unwrap(), expected),
                "s {s} edge {a}-{b}"
            );
            // Both children of a sharp edge carry s − 1 (at least 0).
            for end in [e.a, e.b] {
                let child = edge_between(&m, end, mid);
                let got = m.attr(&crease, child).unwrap().copied();
                if sharp {
                    let want = if s.is_infinite() {
                        s
                    } else {
                        (s - 1.0).max(0.0)
                    };
                    assert_eq!(got, Some(want), "s {s}");
                } else {
                    assert_eq!(got, None);
                }
            }
        }
        m.validate().unwrap();
    }
}

#[test]
fn loop_hard_crease_on_a_tetrahedron() {
    let mut m = meshloom::shapes::tetrahedron();
    let old: Vec<VertexKey> = m.vertices().collect();
    let p: Vec<[f64; 3]> = old.iter().map(|&v| m.position(v).unwrap()).collect();
    let crease = m.add_edge_attr::<f64>("crease").unwrap();
    // The three edges of the triangle 0, 1, 2.
    for (a, b) in [(0, 1), (1, 2), (2, 0)] {
        let e = edge_between(&m, old[a], old[b]);
        m.set_attr(&crease, e, f64::INFINITY).unwrap();
    }
    let opts = SubdivisionOptions::default().crease_column(Some("crease".into()));
    let r = loop_subdivide(&mut m, &opts, Progress::none()).unwrap();
    assert_eq!(r.levels[0].crease_vertices, 3);
    for (i, a, b) in [(0, 1, 2), (1, 0, 2), (2, 0, 1)] {
        let expected = add(scale(p[i], 0.75), scale(add(p[a], p[b]), 0.125));
        assert!(close(m.position(old[i]).unwrap(), expected));
    }
    let mid = edge_point(&m, &old, old[0], old[1]);
    assert!(close(m.position(mid).unwrap(), scale(add(p[0], p[1]), 0.5)));
    // Vertex 3 has no sharp edge: Loop's smooth rule, β = 3/16.
    let expected = add(
        scale(p[3], 1.0 - 9.0 / 16.0),
        scale(add(add(p[0], p[1]), p[2]), 3.0 / 16.0),
    );
    assert!(close(m.position(old[3]).unwrap(), expected));
    // A second level keeps the crease: the three old vertices stay on
    // their creased triangle's plane.
    loop_subdivide(&mut m, &opts, Progress::none()).unwrap();
    let n = {
        let (u, w) = (add(p[1], scale(p[0], -1.0)), add(p[2], scale(p[0], -1.0)));
        [
            u[1] * w[2] - u[2] * w[1],
            u[2] * w[0] - u[0] * w[2],
            u[0] * w[1] - u[1] * w[0],
        ]
    };
    for &v in &old[..3] {
        let d = add(m.position(v).unwrap(), scale(p[0], -1.0));
        assert!((d[0] * n[0] + d[1] * n[1] + d[2] * n[2]).abs() < 1e-12);
    }
}

#[test]
fn nan_sharpness_and_missing_columns_are_refused() {
    let mut m = meshloom::shapes::cube();
    let crease = m.add_edge_attr::<f64>("crease").unwrap();
    let e = m.edges().next().unwrap();
    m.set_attr(&crease, e, f64::NAN).unwrap();
    let snap = snapshot(&m);
    let opts = SubdivisionOptions::default().crease_column(Some("crease".into()));
    for scheme in [catmull_clark as Scheme, loop_subdivide] {
        assert!(scheme(&mut m, &opts, Progress::none()).is_err());
        assert_eq!(snapshot(&m), snap);
    }
    let opts = SubdivisionOptions::default().crease_column(Some("nope".into()));
    let err = catmull_clark(&mut m, &opts, Progress::none()).unwrap_err();
    assert!(matches!(err, meshloom::Error::AttributeMissing { .. }));
    assert_eq!(snapshot(&m), snap);
}

// ----- convergence ----------------------------------------------------------

/// The limit position of vertex `v` of an all-quad mesh (Halstead, Kass
/// and DeRose 1993): (n² v + 4 Σ eᵢ + Σ fᵢ) / (n (n + 5)), eᵢ its
/// neighbours, fᵢ the corners opposite it in its quads.
fn cc_limit(m: &Mesh, v: VertexKey) -> [f64; 3] {
    let view = m.vertex(v).unwrap();
    let n = view.degree() as f64;
    let mut sum = scale(m.position(v).unwrap(), n * n);
    for u in view.neighbors() {
        sum = add(sum, scale(m.position(u).unwrap(), 4.0));
    }
    for f in view.faces() {
        let vs: Vec<VertexKey> = m.face(f).unwrap().vertices().collect();
        assert_eq!(vs.len(), 4);
        let i = vs.iter().position(|&u| u == v).unwrap();
        sum = add(sum, m.position(vs[(i + 2) % 4]).unwrap());
    }
    scale(sum, 1.0 / (n * (n + 5.0)))
}

#[test]
fn catmull_clark_cube_approaches_its_limit() {
    let mut m = meshloom::shapes::cube();
    let v = m.vertices().next().unwrap();
    catmull_clark(&mut m, &SubdivisionOptions::default(), Progress::none()).unwrap();
    let limit = cc_limit(&m, v);
    let dist = |m: &Mesh| {
        let p = m.position(v).unwrap();
        (0..3)
            .map(|k| (p[k] - limit[k]).powi(2))
            .sum::<f64>()
            .sqrt()
    };
    let mut last = dist(&m);
    assert!(last > 0.01);
    for _ in 0..5 {
        catmull_clark(&mut m, &SubdivisionOptions::default(), Progress::none()).unwrap();
        let d = dist(&m);
        assert!(d < 0.5 * last, "{d} vs {last}");
        // The limit stencil gives the same point at every level.
        assert!(close_to(cc_limit(&m, v), limit, 1e-12));
        last = d;
    }
    assert!(last < 1e-3);
}

fn close_to(a: [f64; 3], b: [f64; 3], tol: f64) -> bool {
    (0..3).all(|i| (a[i] - b[i]).abs() < tol)
}

/// Loop of an icosahedron converges: the 12 original vertices (tracked by
/// their keys) move less at each level, by about the subdominant
/// eigenvalue of the valence-5 stencil, and the radius spread settles
/// (its change shrinks from level 3 on).
///
/// The spread itself does not shrink: the limit surface is not a sphere.
/// An independent implementation in Python gives the same spreads
/// (0.00240, 0.00560, 0.00940, 0.01096, 0.01149 for levels 1 to 5).
#[test]
fn loop_icosahedron_converges() {
    let spread = |m: &Mesh| {
        let r: Vec<f64> = m
            .vertices()
            .map(|v| {
                m.position(v)
                    .unwrap()
                    .iter()
                    .map(|c| c * c)
                    .sum::<f64>()
                    .sqrt()
            })
            .collect();
        let (lo, hi) = r
            .iter()
            .fold((f64::MAX, 0.0f64), |(lo, hi), &x| (lo.min(x), hi.max(x)));
        (hi - lo) / (r.iter().sum::<f64>() / r.len() as f64)
    };
    let mut m = meshloom::shapes::icosahedron();
    let old: Vec<VertexKey> = m.vertices().collect();
    let at = |m: &Mesh| -> Vec<[f64; 3]> { old.iter().map(|&v| m.position(v).unwrap()).collect() };
    let mut spreads = vec![spread(&m)];
    let mut moves = Vec::new();
    for _ in 0..5 {
        let before = at(&m);
        loop_subdivide(&mut m, &SubdivisionOptions::default(), Progress::none()).unwrap();
        let after = at(&m);
        let moved = before
            .iter()
            .zip(&after)
            .map(|(a, b)| (0..3).map(|k| (a[k] - b[k]).powi(2)).sum::<f64>().sqrt())
            .fold(0.0f64, f64::max);
        moves.push(moved);
        spreads.push(spread(&m));
    }
    for w in moves.windows(2) {
        assert!(w[1] < 0.7 * w[0], "{moves:?}");
    }
    let changes: Vec<f64> = spreads.windows(2).map(|w| (w[1] - w[0]).abs()).collect();
    for w in changes[2..].windows(2) {
        assert!(w[1] < w[0], "{spreads:?}");
    }
}

// ----- attributes -----------------------------------------------------------

/// Corner UV of `h` as a pair (None when absent).
fn uv(m: &Mesh, h: meshloom::HalfedgeKey) -> Option<Vec<f64>> {
    m.attr_value("texcoord", h).unwrap().map(|v| match v {
        Value::List(l) => l.iter().map(|x| x.as_f64().unwrap()).collect(),
        other => vec![other.as_f64().unwrap()],
    })
}

/// Edges whose two sides disagree at either end.
fn seams(m: &Mesh) -> usize {
    m.edges()
        .filter(|&e| {
            let ev = m.edge(e).unwrap();
            if ev.is_boundary() {
                return false;
            }
            let (h, t) = (ev.halfedge(0), ev.halfedge(1));
            uv(m, h.key()) != uv(m, t.next().key()) || uv(m, t.key()) != uv(m, h.next().key())
        })
        .count()
}

#[test]
fn spider_uv_seams_stay_seams() {
    let path = mesh_path("textured/spider.obj");
    let mut m = meshloom::io::read_with(&path, &meshloom::io::ReadOptions::repair_all())
        .unwrap()
        .0;
    let before = seams(&m);
    assert!(before > 10, "the spider has {before} seams");
    for scheme in [catmull_clark as Scheme, loop_subdivide] {
        let mut m2 = m.clone();
        if scheme(&mut m2, &SubdivisionOptions::default(), Progress::none()).is_err() {
            // Loop takes triangles only.
            assert!(m.faces().any(|f| m.face(f).unwrap().degree() != 3));
            continue;
        }
        m2.validate().unwrap();
        // A seam splits into two seams; no new seam appears inside a face.
        assert_eq!(seams(&m2), 2 * before);
    }
    catmull_clark(
        &mut m,
        &SubdivisionOptions::default().levels(2),
        Progress::none(),
    )
    .unwrap();
    assert_eq!(seams(&m), 4 * before);
}

/// Two unit quads side by side with UV charts [0,1]² and [2,3]×[0,1]: the
/// shared edge is a seam.
fn seam_quads() -> Mesh {
    let p = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [2.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [1.0, 1.0, 0.0],
        [2.0, 1.0, 0.0],
    ];
    let mut m = Mesh::from_polygons(&p, &[[0u32, 1, 4, 3], [1, 2, 5, 4]]).unwrap();
    let tc = m.add_halfedge_attr::<[f64; 2]>("texcoord").unwrap();
    let faces: Vec<FaceKey> = m.faces().collect();
    for (i, f) in faces.into_iter().enumerate() {
        let hs: Vec<_> = m.face(f).unwrap().halfedges().collect();
        for h in hs {
            let q = m.position(m.halfedge(h).unwrap().origin().key()).unwrap();
            let u = q[0] - i as f64 + 2.0 * i as f64;
            m.set_attr(&tc, h, [u, q[1]]).unwrap();
        }
    }
    m
}

#[test]
fn hand_made_seam_stays_a_seam() {
    for scheme in [catmull_clark as Scheme] {
        let mut m = seam_quads();
        assert_eq!(seams(&m), 1);
        scheme(
            &mut m,
            &SubdivisionOptions::default().levels(2),
            Progress::none(),
        )
        .unwrap();
        assert_eq!(seams(&m), 4);
        let tc = m
            .attr_handle::<meshloom::HalfedgeKey, [f64; 2], meshloom::attr::Interpolate>("texcoord")
            .unwrap();
        let (mut left, mut right) = (0, 0);
        for f in m.faces() {
            let us: Vec<f64> = m
                .face(f)
                .unwrap()
                .halfedges()
                .map(|h| m.attr(&tc, h).unwrap().expect("every corner has a UV")[0])
                .collect();
            if us.iter().all(|u| (0.0..=1.0).contains(u)) {
                left += 1;
            } else {
                assert!(us.iter().all(|u| (2.0..=3.0).contains(u)), "{us:?}");
                right += 1;
            }
        }
        assert_eq!((left, right), (16, 16));
    }
}

/// Material ids, a conserved face total, a hard-edge flag and a corner
/// column together, through both schemes.
#[test]
fn face_and_edge_columns_follow_their_rules() {
    for (scheme, mut m, per_face) in [
        (catmull_clark as Scheme, meshloom::shapes::cube(), 4usize),
        (loop_subdivide, meshloom::shapes::icosahedron(), 4),
        (catmull_clark, meshloom::shapes::icosahedron(), 3),
    ] {
        let totals = add_totals(&mut m);
        let material = m.add_face_attr::<u32>("material").unwrap();
        let faces: Vec<FaceKey> = m.faces().collect();
        for (i, &f) in faces.iter().enumerate() {
            m.set_attr(&material, f, (i % 3) as u32).unwrap();
        }
        let hard = m.add_edge_attr::<bool>("hard").unwrap();
        let edges: Vec<EdgeKey> = m.edges().collect();
        let flagged: Vec<[VertexKey; 2]> = edges
            .iter()
            .step_by(4)
            .map(|&e| m.edge(e).unwrap().vertices())
            .collect();
        for &e in edges.iter().step_by(4) {
            m.set_attr(&hard, e, true).unwrap();
        }
        let per_material: Vec<usize> = (0..3)
            .map(|k| faces.iter().enumerate().filter(|(i, _)| i % 3 == k).count())
            .collect();
        let total = face_total(&m, &totals);
        scheme(&mut m, &SubdivisionOptions::default(), Progress::none()).unwrap();
        assert!((face_total(&m, &totals) - total).abs() < 1e-9);
        for k in 0..3u32 {
            let n = m
                .faces()
                .filter(|&f| m.attr(&material, f).unwrap() == Some(&k))
                .count();
            assert_eq!(n, per_face * per_material[k as usize]);
        }
        assert!(m.faces().all(|f| m.attr(&material, f).unwrap().is_some()));
        let now: Vec<EdgeKey> = m
            .edges()
            .filter(|&e| m.attr(&hard, e).unwrap() == Some(&true))
            .collect();
        assert_eq!(now.len(), 2 * flagged.len());
        // Each flagged child runs from an end of a flagged parent to its
        // edge point.
        for [a, b] in flagged {
            let old: Vec<VertexKey> = vec![a, b];
            let mid = m
                .vertex(a)
                .unwrap()
                .neighbors()
                .find(|&u| m.vertex(b).unwrap().neighbors().any(|w| w == u))
                .unwrap();
            let _ = old;
            for end in [a, b] {
                let e = edge_between(&m, end, mid);
                assert_eq!(m.attr(&hard, e).unwrap(), Some(&true));
            }
        }
        m.validate().unwrap();
    }
}

#[test]
fn vertex_columns_smooth_or_linear() {
    for how in [VertexInterpolation::Smooth, VertexInterpolation::Linear] {
        let mut m = meshloom::shapes::cube();
        let x = m.add_vertex_attr::<f64>("x").unwrap();
        let old: Vec<VertexKey> = m.vertices().collect();
        for &v in &old {
            let px = m.position(v).unwrap()[0];
            m.set_attr(&x, v, px).unwrap();
        }
        let before: Vec<f64> = old.iter().map(|&v| m.position(v).unwrap()[0]).collect();
        let edges = old_edges(&m);
        let mut opts = SubdivisionOptions::default();
        opts.vertex_data = opts.vertex_data.with("x", how);
        catmull_clark(&mut m, &opts, Progress::none()).unwrap();
        for (i, &v) in old.iter().enumerate() {
            let got = *m.attr(&x, v).unwrap().unwrap();
            let want = match how {
                VertexInterpolation::Smooth => m.position(v).unwrap()[0],
                VertexInterpolation::Linear => before[i],
            };
            assert!((got - want).abs() < 1e-12);
        }
        for e in &edges {
            let mid = edge_point(&m, &old, e.a, e.b);
            let got = *m.attr(&x, mid).unwrap().unwrap();
            let want = match how {
                VertexInterpolation::Smooth => m.position(mid).unwrap()[0],
                VertexInterpolation::Linear => {
                    let (a, b) = (
                        before[old.iter().position(|&o| o == e.a).unwrap()],
                        before[old.iter().position(|&o| o == e.b).unwrap()],
                    );
                    (a + b) / 2.0
                }
            };
            assert!((got - want).abs() < 1e-12);
        }
    }
}

// ----- cancellation ---------------------------------------------------------

#[test]
fn cancel_leaves_the_mesh_as_it_was() {
    for (scheme, per_level) in [(catmull_clark as Scheme, 3 * 4), (loop_subdivide, 16)] {
        let mut m = meshloom::shapes::icosphere(2);
        let material = m.add_face_attr::<u32>("material").unwrap();
        let f0 = m.faces().next().unwrap();
        m.set_attr(&material, f0, 7).unwrap();
        let e0 = m.edges().next().unwrap();
        let h0 = m.halfedges().next().unwrap();
        let snap = snapshot(&m);
        let opts = SubdivisionOptions::default().levels(2);
        let mut cancelled = 0;
        for k in 0.. {
            let mut calls = 0;
            let mut cb = |_: &meshloom::algo::ProgressInfo<'_>| {
                calls += 1;
                if calls > k {
                    Flow::Cancel
                } else {
                    Flow::Continue
                }
            };
            match scheme(&mut m, &opts, Progress::new(&mut cb)) {
                Ok(_) => break,
                Err(meshloom::Error::Cancelled { .. }) => {}
                Err(e) => panic!("{e}"),
            }
            cancelled += 1;
            assert_eq!(snapshot(&m), snap, "cancelled at report {k}");
            assert_eq!(m.attr(&material, f0).unwrap(), Some(&7));
            assert!(m.contains_edge(e0) && m.contains_halfedge(h0));
            m.validate().unwrap();
        }
        // After the last (uncancelled) run the mesh is subdivided.
        assert_eq!(m.face_count(), 320 * per_level);
        assert!(cancelled >= 5, "{cancelled}");
    }
}

// ----- √3 and midpoint ------------------------------------------------------

use meshloom::algo::{midpoint_subdivide, sqrt3_subdivide, MidpointFaces, MidpointOptions};

#[test]
fn sqrt3_counts_topology_and_flips() {
    let mut meshes = vec![
        meshloom::shapes::tetrahedron(),
        meshloom::shapes::octahedron(),
        meshloom::shapes::icosphere(2),
    ];
    for file in [
        "closed/cgal_icosahedron.off",
        "closed/cgal_sphere966.off",
        "closed/openmesh_sphere840.ply",
    ] {
        meshes.push(read_off(&mesh_path(file)));
    }
    for mut m in meshes {
        let before = topology(&m);
        for _ in 0..2 {
            let (v, e, f, h) = counts(&m);
            let old: Vec<VertexKey> = m.vertices().collect();
            sqrt3_subdivide(&mut m, &SubdivisionOptions::default(), Progress::none()).unwrap();
            assert_eq!(counts(&m), (v + f, 3 * e, 3 * f, h));
            m.validate().unwrap();
            assert_eq!(topology(&m), before);
            assert!(m.faces().all(|f| m.face(f).unwrap().degree() == 3));
            // Every old edge was flipped away: no two old vertices are
            // joined, and each old vertex's neighbours are face points.
            for &a in &old {
                assert!(m.vertex(a).unwrap().neighbors().all(|u| !old.contains(&u)));
            }
        }
    }
}

/// √3 on a tetrahedron: α₃ = (4 − 2 cos 120°)/9 = 5/9, so an old vertex
/// goes to 4/9 v + 5/27 Σ uᵢ; face points are centroids.
#[test]
fn sqrt3_stencils_on_a_tetrahedron() {
    let mut m = meshloom::shapes::tetrahedron();
    let old: Vec<VertexKey> = m.vertices().collect();
    let p: Vec<[f64; 3]> = old.iter().map(|&v| m.position(v).unwrap()).collect();
    let centroids: Vec<[f64; 3]> = m
        .faces()
        .map(|f| {
            let ps: Vec<_> = m
                .face(f)
                .unwrap()
                .vertices()
                .map(|v| m.position(v).unwrap())
                .collect();
            mean(&ps)
        })
        .collect();
    sqrt3_subdivide(&mut m, &SubdivisionOptions::default(), Progress::none()).unwrap();
    for (i, &v) in old.iter().enumerate() {
        let others = (0..4)
            .filter(|&j| j != i)
            .fold([0.0; 3], |s, j| add(s, p[j]));
        let expected = add(scale(p[i], 4.0 / 9.0), scale(others, 5.0 / 27.0));
        assert!(close(m.position(v).unwrap(), expected), "vertex {i}");
    }
    let new: Vec<[f64; 3]> = m
        .vertices()
        .filter(|v| !old.contains(v))
        .map(|v| m.position(v).unwrap())
        .collect();
    assert_eq!(new.len(), 4);
    for c in &centroids {
        assert_eq!(new.iter().filter(|&&q| close(q, *c)).count(), 1);
    }
}

/// Open triangle meshes with boundaries of every kind: a small grid, a fan,
/// a one-ring and the real boundary meshes.
fn open_triangle_meshes() -> Vec<Mesh> {
    let mut meshes = vec![
        meshloom::shapes::grid(5, 4, meshloom::shapes::GridFaces::Triangles),
        common::boundary_fan(),
        common::one_ring(),
    ];
    for file in [
        "boundary/cgal_mesh_with_border.off",
        "boundary/cgal_open_cube.off",
        "boundary/cgal_triangular_hole.off",
        "boundary/cgal_holes.off",
    ] {
        meshes.push(read_off(&mesh_path(file)));
    }
    meshes
}

/// Boundary edges are kept (not flipped), boundary vertices stay put.
#[test]
fn sqrt3_keeps_the_boundary() {
    for mut m in open_triangle_meshes() {
        let before = topology(&m);
        let boundary: Vec<(VertexKey, [f64; 3])> = m
            .vertices()
            .filter(|&v| m.vertex(v).unwrap().is_boundary())
            .map(|v| (v, m.position(v).unwrap()))
            .collect();
        let boundary_edges = m
            .edges()
            .filter(|&e| m.edge(e).unwrap().is_boundary())
            .count();
        for _ in 0..2 {
            let (v, e, f, h) = counts(&m);
            sqrt3_subdivide(&mut m, &SubdivisionOptions::default(), Progress::none()).unwrap();
            assert_eq!(counts(&m), (v + f, e + 3 * f, 3 * f, h));
            m.validate().unwrap();
            assert_eq!(topology(&m), before);
        }
        for (v, p) in &boundary {
            assert_eq!(m.position(*v).unwrap(), *p);
        }
        let now = m
            .edges()
            .filter(|&e| m.edge(e).unwrap().is_boundary())
            .count();
        assert_eq!(now, boundary_edges);
    }
}

#[test]
fn sqrt3_refuses_polygons_and_creases() {
    let opts = SubdivisionOptions::default();
    for mut m in [meshloom::shapes::cube(), quad_strip()] {
        let snap = snapshot(&m);
        let err = sqrt3_subdivide(&mut m, &opts, Progress::none()).unwrap_err();
        assert!(matches!(err, meshloom::Error::Unsuitable { .. }), "{err}");
        assert_eq!(snapshot(&m), snap);
    }
    let (mut m, _, _) = creased_cube(1.0);
    let opts = SubdivisionOptions::default().crease_column(Some("crease".into()));
    assert!(sqrt3_subdivide(&mut m, &opts, Progress::none()).is_err());
}

#[test]
fn sqrt3_face_columns_and_corner_vertices() {
    let mut m = meshloom::shapes::icosphere(1);
    let totals = add_totals(&mut m);
    let material = m.add_face_attr::<u32>("material").unwrap();
    let faces: Vec<FaceKey> = m.faces().collect();
    for &f in &faces {
        m.set_attr(&material, f, 5).unwrap();
    }
    let pin = m.add_vertex_attr::<bool>("pin").unwrap();
    let v0 = m.vertices().next().unwrap();
    let p0 = m.position(v0).unwrap();
    m.set_attr(&pin, v0, true).unwrap();
    let total = face_total(&m, &totals);
    let opts = SubdivisionOptions::default()
        .levels(2)
        .corner_column(Some("pin".into()));
    let r = sqrt3_subdivide(&mut m, &opts, Progress::none()).unwrap();
    assert_eq!(r.levels[0].corner_vertices, 1);
    assert!((face_total(&m, &totals) - total).abs() < 1e-9);
    assert!(m.faces().all(|f| m.attr(&material, f).unwrap() == Some(&5)));
    assert_eq!(m.position(v0).unwrap(), p0);
    m.validate().unwrap();
}

#[test]
fn midpoint_keeps_the_shape_and_splits_columns() {
    // (how, mesh, children per face, whether faces get a centre point)
    for (faces, mut m, per_face, face_points) in [
        (
            MidpointFaces::Auto,
            meshloom::shapes::icosahedron(),
            4usize,
            false,
        ),
        (MidpointFaces::Triangles, common::boundary_fan(), 4, false),
        (
            MidpointFaces::Quads,
            meshloom::shapes::icosahedron(),
            3,
            true,
        ),
        (MidpointFaces::Auto, quad_strip(), 4, true),
    ] {
        let totals = add_totals(&mut m);
        let total = face_total(&m, &totals);
        let old: Vec<VertexKey> = m.vertices().collect();
        let p: Vec<[f64; 3]> = old.iter().map(|&v| m.position(v).unwrap()).collect();
        let edges = old_edges(&m);
        let before = topology(&m);
        let (v, e, f, h) = counts(&m);
        let opts = MidpointOptions::default().levels(1).faces(faces);
        midpoint_subdivide(&mut m, &opts, Progress::none()).unwrap();
        let new_v = if face_points { v + e + f } else { v + e };
        assert_eq!(counts(&m).0, new_v, "{faces:?}");
        assert_eq!(m.face_count(), per_face * f);
        assert_eq!(counts(&m).3, h);
        assert_eq!(topology(&m), before);
        for (i, &v) in old.iter().enumerate() {
            assert_eq!(m.position(v).unwrap(), p[i]);
        }
        for ed in &edges {
            let pos = |v: VertexKey| p[old.iter().position(|&o| o == v).unwrap()];
            let mid = edge_point(&m, &old, ed.a, ed.b);
            assert!(close(
                m.position(mid).unwrap(),
                scale(add(pos(ed.a), pos(ed.b)), 0.5)
            ));
        }
        assert!((face_total(&m, &totals) - total).abs() < 1e-9);
        m.validate().unwrap();
    }
    // Triangles only with MidpointFaces::Triangles; the mesh is kept.
    let mut m = meshloom::shapes::cube();
    let snap = snapshot(&m);
    let opts = MidpointOptions::default()
        .levels(1)
        .faces(MidpointFaces::Triangles);
    assert!(midpoint_subdivide(&mut m, &opts, Progress::none()).is_err());
    assert_eq!(snapshot(&m), snap);
}

#[test]
fn midpoint_seam_stays_a_seam() {
    let mut m = seam_quads();
    midpoint_subdivide(
        &mut m,
        &MidpointOptions::default().levels(3),
        Progress::none(),
    )
    .unwrap();
    assert_eq!(seams(&m), 8);
}

#[test]
fn cancel_sqrt3_and_midpoint() {
    let runs: [(&str, Scheme); 2] = [
        ("sqrt3", sqrt3_subdivide),
        ("midpoint", |m, o, p| {
            midpoint_subdivide(m, &MidpointOptions::default().levels(o.levels), p)
        }),
    ];
    for (name, scheme) in runs {
        let mut m = meshloom::shapes::icosphere(2);
        let snap = snapshot(&m);
        let mut cancelled = 0;
        for k in 0.. {
            let mut calls = 0;
            let mut cb = |_: &meshloom::algo::ProgressInfo<'_>| {
                calls += 1;
                if calls > k {
                    Flow::Cancel
                } else {
                    Flow::Continue
                }
            };
            match scheme(
                &mut m,
                &SubdivisionOptions::default().levels(2),
                Progress::new(&mut cb),
            ) {
                Ok(_) => break,
                Err(meshloom::Error::Cancelled { .. }) => {}
                Err(e) => panic!("{name}: {e}"),
            }
            cancelled += 1;
            assert_eq!(snapshot(&m), snap, "{name} cancelled at report {k}");
        }
        assert!(cancelled >= 3, "{name}: {cancelled}");
        assert!(m.face_count() > 320);
    }
}

/// An icosphere with two UV charts: the faces whose centroid lies above
/// z = 0 take `(x, y)`, the others `(x + 10, y)`; the edges between the
/// two halves are seams.
fn two_chart_sphere() -> Mesh {
    let mut m = meshloom::shapes::icosphere(2);
    let tc = m.add_halfedge_attr::<[f64; 2]>("texcoord").unwrap();
    let faces: Vec<FaceKey> = m.faces().collect();
    for f in faces {
        let hs: Vec<_> = m.face(f).unwrap().halfedges().collect();
        let at = |m: &Mesh, h| m.position(m.halfedge(h).unwrap().origin().key()).unwrap();
        let z: f64 = hs.iter().map(|&h| at(&m, h)[2]).sum();
        let shift = if z > 0.0 { 0.0 } else { 10.0 };
        for h in hs {
            let q = at(&m, h);
            m.set_attr(&tc, h, [q[0] + shift, q[1]]).unwrap();
        }
    }
    m
}

#[test]
fn sqrt3_keeps_uv_seams() {
    let mut m = two_chart_sphere();
    let before = seams(&m);
    assert!(before >= 8, "{before} seams");
    let (v, f) = (m.vertex_count(), m.face_count());
    sqrt3_subdivide(
        &mut m,
        &SubdivisionOptions::default().levels(2),
        Progress::none(),
    )
    .unwrap();
    m.validate().unwrap();
    assert_eq!((m.vertex_count(), m.face_count()), (v + f + 3 * f, 9 * f));
    // The seam edges are kept, not flipped away: as many seams as before
    // and none inside a chart.
    assert_eq!(seams(&m), before);
    // Every triangle lies in one chart: no corner mixes the two.
    let tc = m
        .attr_handle::<meshloom::HalfedgeKey, [f64; 2], meshloom::attr::Interpolate>("texcoord")
        .unwrap();
    let (mut upper, mut lower) = (0, 0);
    for f in m.faces() {
        let us: Vec<f64> = m
            .face(f)
            .unwrap()
            .halfedges()
            .map(|h| m.attr(&tc, h).unwrap().expect("every corner has a UV")[0])
            .collect();
        if us.iter().all(|&u| u.abs() <= 1.0) {
            upper += 1;
        } else {
            assert!(us.iter().all(|&u| (9.0..=11.0).contains(&u)), "{us:?}");
            lower += 1;
        }
    }
    assert_eq!(upper + lower, 9 * f);
    assert!(upper > 0 && lower > 0);
    // Without the column the same sphere flips every edge.
    let mut plain = meshloom::shapes::icosphere(2);
    sqrt3_subdivide(&mut plain, &SubdivisionOptions::default(), Progress::none()).unwrap();
    let mut seamed = two_chart_sphere();
    sqrt3_subdivide(
        &mut seamed,
        &SubdivisionOptions::default(),
        Progress::none(),
    )
    .unwrap();
    assert_eq!(plain.edge_count(), seamed.edge_count());
    assert_eq!(seams(&seamed), before);
}

// ----- √3 boundary trisection -------------------------------------------------

/// A small open triangle grid with a bump, so that every stencil moves
/// something.
fn bumpy_grid() -> Mesh {
    let mut m = meshloom::shapes::grid(4, 3, meshloom::shapes::GridFaces::Triangles);
    let vs: Vec<VertexKey> = m.vertices().collect();
    for (i, v) in vs.into_iter().enumerate() {
        let p = m.position(v).unwrap();
        let z = 0.1 * (p[0] * 1.7).sin() + 0.05 * (p[1] * 2.3).cos() + 0.01 * i as f64;
        m.set_position(v, [p[0], p[1], z]).unwrap();
    }
    m
}

fn boundary_edge_count(m: &Mesh) -> usize {
    m.edges()
        .filter(|&e| m.edge(e).unwrap().is_boundary())
        .count()
}

/// The vertex loops of the holes.
fn hole_loops(m: &Mesh) -> Vec<Vec<VertexKey>> {
    m.faces_and_holes()
        .filter(|&f| m.face(f).unwrap().is_hole())
        .map(|f| m.face(f).unwrap().vertices().collect())
        .collect()
}

/// Two levels in one call: the first keeps the boundary, the second
/// trisects every boundary edge (V + F + 2B, E + 3F + 4B, 3F + 2B).
#[test]
fn sqrt3_trisects_the_boundary_every_second_level() {
    let mut meshes = open_triangle_meshes();
    meshes.push(bumpy_grid());
    for mut m in meshes {
        let before = topology(&m);
        let (v, e, f, h) = counts(&m);
        let b = boundary_edge_count(&m);
        assert!(b > 0);
        let r = sqrt3_subdivide(
            &mut m,
            &SubdivisionOptions::default().levels(2),
            Progress::none(),
        )
        .unwrap();
        m.validate().unwrap();
        assert_eq!(topology(&m), before);
        let (v1, e1, f1) = (v + f, e + 3 * f, 3 * f);
        assert_eq!(
            counts(&m),
            (v1 + f1 + 2 * b, e1 + 3 * f1 + 4 * b, 3 * f1 + 2 * b, h)
        );
        assert_eq!(boundary_edge_count(&m), 3 * b);
        assert!(!r.levels[0].boundary_trisected && r.levels[1].boundary_trisected);
        assert!(m.faces().all(|f| m.face(f).unwrap().degree() == 3));
        // Four levels: the boundary is trisected twice.
        let mut m4 = m.clone();
        sqrt3_subdivide(
            &mut m4,
            &SubdivisionOptions::default().levels(2),
            Progress::none(),
        )
        .unwrap();
        m4.validate().unwrap();
        assert_eq!(boundary_edge_count(&m4), 9 * b);
    }
}

/// The second level's boundary against the ternary cubic B-spline rules,
/// computed here from the first level's mesh: an old boundary vertex goes
/// to (4 a + 19 v + 4 b) / 27, the point a third along a → b to
/// (p + 16 a + 10 b) / 27 with p the boundary vertex before a; interior
/// vertices take Kobbelt's rule, face points are centroids.
#[test]
fn sqrt3_boundary_stencils_on_an_open_mesh() {
    let mut one = bumpy_grid();
    sqrt3_subdivide(&mut one, &SubdivisionOptions::default(), Progress::none()).unwrap();
    let mut two = bumpy_grid();
    sqrt3_subdivide(
        &mut two,
        &SubdivisionOptions::default().levels(2),
        Progress::none(),
    )
    .unwrap();
    let old: Vec<VertexKey> = one.vertices().collect();
    let p = |v: VertexKey| one.position(v).unwrap();
    let q = |v: VertexKey| two.position(v).unwrap();
    let loops = hole_loops(&two);
    assert_eq!(loops.len(), 1);
    let ring = &loops[0];
    let n = ring.len();
    assert_eq!(n, 3 * boundary_edge_count(&one));
    // Old vertices sit at every third place of the new boundary loop.
    let start = ring.iter().position(|v| old.contains(v)).unwrap();
    let ring: Vec<VertexKey> = (0..n).map(|i| ring[(start + i) % n]).collect();
    let corners: Vec<VertexKey> = ring.iter().step_by(3).copied().collect();
    assert!(ring
        .iter()
        .enumerate()
        .all(|(i, v)| old.contains(v) == (i % 3 == 0)));
    let k = corners.len();
    let mut checked = 0;
    for i in 0..k {
        let (before, a, b, after) = (
            corners[(i + k - 1) % k],
            corners[i],
            corners[(i + 1) % k],
            corners[(i + 2) % k],
        );
        let expected_a = scale(
            add(
                add(scale(p(before), 4.0), scale(p(a), 19.0)),
                scale(p(b), 4.0),
            ),
            1.0 / 27.0,
        );
        assert!(close(q(a), expected_a), "old boundary vertex {i}");
        let (x1, x2) = (ring[3 * i + 1], ring[3 * i + 2]);
        let near_a = scale(
            add(add(p(before), scale(p(a), 16.0)), scale(p(b), 10.0)),
            1.0 / 27.0,
        );
        let near_b = scale(
            add(add(scale(p(a), 10.0), scale(p(b), 16.0)), p(after)),
            1.0 / 27.0,
        );
        assert!(close(q(x1), near_a), "point a third along edge {i}");
        assert!(close(q(x2), near_b), "point two thirds along edge {i}");
        checked += 3;
    }
    assert_eq!(checked, n);
    // An interior vertex: Kobbelt's rule over its first-level neighbours.
    let inner: Vec<VertexKey> = old
        .iter()
        .copied()
        .filter(|&v| !one.vertex(v).unwrap().is_boundary())
        .collect();
    assert!(!inner.is_empty());
    for v in inner {
        let nb: Vec<VertexKey> = one.vertex(v).unwrap().neighbors().collect();
        let deg = nb.len() as f64;
        let alpha = (4.0 - 2.0 * (std::f64::consts::TAU / deg).cos()) / 9.0;
        let sum = nb.iter().fold([0.0; 3], |s, &u| add(s, p(u)));
        let expected = add(scale(p(v), 1.0 - alpha), scale(sum, alpha / deg));
        assert!(close(q(v), expected));
    }
    // Linear precision: a straight, evenly spaced boundary stays straight
    // and evenly spaced (the new points at thirds), away from the corners.
    let mut flat = meshloom::shapes::grid(7, 2, meshloom::shapes::GridFaces::Triangles);
    sqrt3_subdivide(
        &mut flat,
        &SubdivisionOptions::default().levels(2),
        Progress::none(),
    )
    .unwrap();
    flat.validate().unwrap();
    let on_line = hole_loops(&flat)[0]
        .iter()
        .map(|&v| flat.position(v).unwrap())
        .filter(|p| p[1] == 0.0)
        .count();
    // The bottom side (y = 0) keeps its interior points on the line.
    assert!(on_line >= 3 * 4, "{on_line} points on y = 0");
}

/// UVs along a trisected boundary: the corners at a new boundary point
/// interpolate the two corners of the parent face at the edge's ends (a
/// third and two thirds along), the same in both triangles there; a UV
/// seam inside stays a seam; face and edge columns follow their rules.
#[test]
fn sqrt3_boundary_attributes() {
    let mut m = bumpy_grid();
    // Two charts: faces left of x = 1.5 and the others, shifted by 10.
    let tc = m.add_halfedge_attr::<[f64; 2]>("texcoord").unwrap();
    let flag = m.add_edge_attr::<bool>("hard").unwrap();
    let totals = add_totals(&mut m);
    let faces: Vec<FaceKey> = m.faces().collect();
    for f in faces {
        let hs: Vec<_> = m.face(f).unwrap().halfedges().collect();
        let at = |m: &Mesh, h| m.position(m.halfedge(h).unwrap().origin().key()).unwrap();
        let x: f64 = hs.iter().map(|&h| at(&m, h)[0]).sum::<f64>() / 3.0;
        let shift = if x < 1.5 { 0.0 } else { 10.0 };
        for h in hs {
            let p = at(&m, h);
            m.set_attr(&tc, h, [p[0] + shift, p[1]]).unwrap();
        }
    }
    let edges: Vec<EdgeKey> = m.edges().collect();
    for e in edges {
        if m.edge(e).unwrap().is_boundary() {
            m.set_attr(&flag, e, true).unwrap();
        }
    }
    let seams_before = seams(&m);
    assert!(seams_before >= 2);
    let total = face_total(&m, &totals);
    let mut one = m.clone();
    sqrt3_subdivide(&mut one, &SubdivisionOptions::default(), Progress::none()).unwrap();
    sqrt3_subdivide(
        &mut m,
        &SubdivisionOptions::default().levels(2),
        Progress::none(),
    )
    .unwrap();
    m.validate().unwrap();
    assert_eq!(seams(&m), seams_before);
    assert!((face_total(&m, &totals) - total).abs() < 1e-9);
    // Every boundary edge is flagged (the three children of each), no
    // inside edge is.
    for e in m.edges() {
        let boundary = m.edge(e).unwrap().is_boundary();
        assert_eq!(m.attr(&flag, e).unwrap() == Some(&true), boundary);
    }
    // Corners at the boundary points, from the first level's corners.
    let old: Vec<VertexKey> = one.vertices().collect();
    let uv_at = |m: &Mesh, h: meshloom::HalfedgeKey| *m.attr(&tc, h).unwrap().unwrap();
    let mut checked = 0;
    for e in one.edges() {
        let ev = one.edge(e).unwrap();
        if !ev.is_boundary() {
            continue;
        }
        let inner = [ev.halfedge(0), ev.halfedge(1)]
            .into_iter()
            .find(|h| !h.face().is_hole())
            .unwrap();
        let (a, b) = (inner.origin().key(), inner.dest().key());
        let (ua, ub) = (uv_at(&one, inner.key()), uv_at(&one, inner.next().key()));
        // The new boundary path a -> x1 -> x2 -> b in the second level.
        let fresh_boundary =
            |x: &VertexKey| !old.contains(x) && m.vertex(*x).unwrap().is_boundary();
        let x2_of = |x1: VertexKey| {
            m.vertex(x1)
                .unwrap()
                .neighbors()
                .find(|y| fresh_boundary(y) && m.vertex(*y).unwrap().neighbors().any(|z| z == b))
        };
        let x1 = m
            .vertex(a)
            .unwrap()
            .neighbors()
            .find(|x| fresh_boundary(x) && x2_of(*x).is_some())
            .unwrap();
        let x2 = x2_of(x1).unwrap();
        for (x, t) in [(x1, 1.0 / 3.0), (x2, 2.0 / 3.0)] {
            let expected = [ua[0] + t * (ub[0] - ua[0]), ua[1] + t * (ub[1] - ua[1])];
            let corners: Vec<[f64; 2]> = m
                .vertex(x)
                .unwrap()
                .outgoing()
                .filter(|&h| !m.halfedge(h).unwrap().face().is_hole())
                .map(|h| uv_at(&m, h))
                .collect();
            assert_eq!(corners.len(), 2);
            assert_eq!(corners[0], corners[1], "one value at a boundary point");
            assert!((0..2).all(|i| (corners[0][i] - expected[i]).abs() < 1e-12));
            checked += 1;
        }
    }
    assert_eq!(checked, 2 * boundary_edge_count(&one));
}

/// The boundary loop of a one-hole mesh, starting at an old vertex, as
/// (vertex, whether it is old) — old vertices sit at every third place
/// after a trisecting level.
fn boundary_from_old(m: &Mesh, old: &[VertexKey]) -> Vec<VertexKey> {
    let loops = hole_loops(m);
    assert_eq!(loops.len(), 1);
    let ring = &loops[0];
    let start = ring.iter().position(|v| old.contains(v)).unwrap();
    (0..ring.len())
        .map(|i| ring[(start + i) % ring.len()])
        .collect()
}

/// Vertex columns through a trisecting level: a colour interpolated like
/// positions ("vertex" data) lands where the positions do, boundary points
/// included; a linear ("varying") column keeps old values, gives a face
/// point the mean of its corners and a boundary point the thirds of its
/// edge.
#[test]
fn sqrt3_boundary_vertex_columns() {
    let mut m = bumpy_grid();
    let colour = m.add_vertex_attr::<[f64; 3]>("colour").unwrap();
    let t = m.add_vertex_attr::<f64>("temperature").unwrap();
    let vs: Vec<VertexKey> = m.vertices().collect();
    for (i, &v) in vs.iter().enumerate() {
        let p = m.position(v).unwrap();
        m.set_attr(&colour, v, p).unwrap();
        m.set_attr(&t, v, p[0] * p[0] + 0.1 * i as f64).unwrap();
    }
    let mut opts = SubdivisionOptions::default().levels(2);
    opts.vertex_data = opts
        .vertex_data
        .with("temperature", VertexInterpolation::Linear);
    let mut one = m.clone();
    sqrt3_subdivide(&mut one, &opts.clone().levels(1), Progress::none()).unwrap();
    let r = sqrt3_subdivide(&mut m, &opts, Progress::none()).unwrap();
    m.validate().unwrap();
    assert!(r.levels[1].boundary_trisected);
    assert_eq!(boundary_edge_count(&m), 3 * boundary_edge_count(&one));
    for v in m.vertices() {
        let (c, p) = (
            *m.attr(&colour, v).unwrap().unwrap(),
            m.position(v).unwrap(),
        );
        assert!(close(c, p), "colour {c:?} at {p:?}");
    }
    let t1 = |v: VertexKey| *one.attr(&t, v).unwrap().unwrap();
    let t2 = |v: VertexKey| *m.attr(&t, v).unwrap().unwrap();
    let old: Vec<VertexKey> = one.vertices().collect();
    for &v in &old {
        assert_eq!(t2(v), t1(v), "an old vertex keeps its value");
    }
    let ring = boundary_from_old(&m, &old);
    let corners: Vec<VertexKey> = ring.iter().step_by(3).copied().collect();
    let k = corners.len();
    for i in 0..k {
        let (a, b) = (corners[i], corners[(i + 1) % k]);
        let (x1, x2) = (ring[3 * i + 1], ring[3 * i + 2]);
        assert!((t2(x1) - (2.0 * t1(a) + t1(b)) / 3.0).abs() < 1e-12);
        assert!((t2(x2) - (t1(a) + 2.0 * t1(b)) / 3.0).abs() < 1e-12);
    }
    // A face point (a new vertex off the boundary) is the mean of the
    // corners of its parent face: three old vertices around it.
    let mut face_points = 0;
    for v in m.vertices() {
        if old.contains(&v) || m.vertex(v).unwrap().is_boundary() {
            continue;
        }
        let corners: Vec<VertexKey> = m
            .vertex(v)
            .unwrap()
            .neighbors()
            .filter(|u| old.contains(u))
            .collect();
        assert_eq!(corners.len(), 3);
        let mean = corners.iter().map(|&u| t1(u)).sum::<f64>() / 3.0;
        assert!((t2(v) - mean).abs() < 1e-12);
        face_points += 1;
    }
    assert_eq!(face_points, one.face_count());
}

/// A boundary vertex that stays (a corner of the grid with
/// `Boundary::CreaseAndCorners`, or one marked in the corner column) ends
/// the boundary curve: it keeps its place through both levels, and the
/// trisection points beside it lie a third of the way along the straight
/// edge.
#[test]
fn sqrt3_boundary_curve_ends_at_corners() {
    let input = bumpy_grid();
    let pinned = input
        .vertices()
        .find(|&v| {
            let view = input.vertex(v).unwrap();
            view.is_boundary() && view.degree() > 3
        })
        .unwrap();
    let mut m = input.clone();
    let pin = m.add_vertex_attr::<bool>("pin").unwrap();
    m.set_attr(&pin, pinned, true).unwrap();
    let opts = SubdivisionOptions::default()
        .levels(2)
        .boundary(Boundary::CreaseAndCorners)
        .corner_column(Some("pin".into()));
    let mut one = m.clone();
    sqrt3_subdivide(&mut one, &opts.clone().levels(1), Progress::none()).unwrap();
    let r = sqrt3_subdivide(&mut m, &opts, Progress::none()).unwrap();
    m.validate().unwrap();
    // The grid's corners of a single face (valence 2) and the pinned one.
    let stays: Vec<VertexKey> = input
        .vertices()
        .filter(|&v| {
            let view = input.vertex(v).unwrap();
            v == pinned || (view.is_boundary() && view.degree() == 2)
        })
        .collect();
    assert!(stays.len() >= 3, "{} corners", stays.len());
    // (The face points next to the pinned vertex inherit its mark.)
    assert!(r.levels[1].corner_vertices >= stays.len());
    for &v in &stays {
        assert_eq!(m.position(v).unwrap(), input.position(v).unwrap());
    }
    let p = |v: VertexKey| one.position(v).unwrap();
    let old: Vec<VertexKey> = one.vertices().collect();
    let ring = boundary_from_old(&m, &old);
    let n = ring.len();
    let mut checked = 0;
    for i in (0..n).step_by(3) {
        let (a, x1, x2, b) = (ring[i], ring[i + 1], ring[i + 2], ring[(i + 3) % n]);
        for (corner, x, other) in [(a, x1, b), (b, x2, a)] {
            if stays.contains(&corner) {
                let expected = add(scale(p(corner), 2.0 / 3.0), scale(p(other), 1.0 / 3.0));
                assert!(close(m.position(x).unwrap(), expected));
                checked += 1;
            }
        }
    }
    assert_eq!(checked, 2 * stays.len());
}
