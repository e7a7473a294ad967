//! Quadric decimation: real closed meshes keep their topology and stay
//! close to the input; UV seams, materials, conserved totals and every
//! guard; targets, errors, cancel; level-of-detail chains.

use std::collections::HashMap;

use meshloom::algo::decimate::{
    decimate, lod_chain, replay, AttributeWeight, DecimateOptions, Keep, LodOptions, StopReason,
    Target,
};
use meshloom::algo::{Flow, Progress};
use meshloom::attr::{Conserved, HalfedgeAttr};
use meshloom::shapes::{self, GridFaces};
use meshloom::{Error, Mesh, VertexKey};

mod common;
use common::hausdorff::{relative_hausdorff, triangles, Sampling};

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

fn read(path: &str) -> Mesh {
    let opts = meshloom::io::ReadOptions::repair_all();
    meshloom::io::read_with(format!("{MESHES}/{path}"), &opts)
        .unwrap()
        .0
}

#[test]
fn real_closed_meshes_keep_topology_reach_the_target_and_stay_close() {
    for (path, bound) in [
        ("closed/cgal_elephant.off", 0.02),
        ("closed/npm-bunny_bunny.off", 0.02),
        ("closed/cgal_sphere966.off", 0.02),
    ] {
        let input = read(path);
        let mut mesh = input.clone();
        let target = (input.vertex_count() as f64 * 0.1).ceil() as usize;
        let r = decimate(
            &mut mesh,
            &DecimateOptions::to(Target::Ratio(0.1)),
            Progress::none(),
        )
        .unwrap();
        mesh.validate().unwrap();
        assert_eq!(
            mesh.euler_characteristic(),
            input.euler_characteristic(),
            "{path}"
        );
        assert_eq!(
            mesh.components().count(),
            input.components().count(),
            "{path}"
        );
        assert_eq!(mesh.hole_count(), 0, "{path}");
        // At the target (a collapse removes one vertex), or a reason why not.
        match r.stopped_by {
            StopReason::Target => assert_eq!(mesh.vertex_count(), target, "{path}"),
            other => panic!(
                "{path}: stopped by {other:?} at {} > {target}: {r:?}",
                mesh.vertex_count()
            ),
        }
        assert_eq!(r.output.vertices, mesh.vertex_count());
        assert_eq!(r.collapses, input.vertex_count() - mesh.vertex_count());
        let h = relative_hausdorff(&input, &mesh, Sampling::Dense);
        assert!(h < bound, "{path}: Hausdorff {h} of the diagonal");
        assert!(r.error > 0.0 && r.error.is_finite());
    }
}

#[test]
fn face_targets_are_reached_within_one_collapse() {
    let mut mesh = shapes::icosphere(3);
    decimate(
        &mut mesh,
        &DecimateOptions::to(Target::Faces(301)),
        Progress::none(),
    )
    .unwrap();
    assert!(
        (300..=301).contains(&mesh.face_count()),
        "{}",
        mesh.face_count()
    );
    let mut mesh = shapes::icosphere(3);
    decimate(
        &mut mesh,
        &DecimateOptions::to(Target::Vertices(100)),
        Progress::none(),
    )
    .unwrap();
    assert_eq!(mesh.vertex_count(), 100);
}

#[test]
fn max_error_stops_and_the_report_says_so() {
    let mut mesh = shapes::icosphere(4);
    let options = DecimateOptions::default()
        .target(Target::None)
        .max_error(Some(0.01));
    let r = decimate(&mut mesh, &options, Progress::none()).unwrap();
    assert_eq!(r.stopped_by, StopReason::MaxError);
    assert!(r.error <= 0.01 && r.error > 0.0, "{r:?}");
    assert!(mesh.vertex_count() < 2562 && mesh.vertex_count() > 12);
    // A smaller bound stops sooner.
    let mut finer = shapes::icosphere(4);
    let options = options.max_error(Some(0.002));
    let rf = decimate(&mut finer, &options, Progress::none()).unwrap();
    assert!(rf.error <= 0.002);
    assert!(finer.vertex_count() > mesh.vertex_count());
    // The error is a mean distance to the merged planes; no vertex is far
    // from the unit sphere.
    for v in mesh.vertices() {
        let p = mesh.position(v).unwrap();
        assert!((dot(p, p).sqrt() - 1.0).abs() < 0.05);
    }
}

#[test]
fn bad_input_is_refused_and_the_mesh_is_unchanged() {
    let mut quads = shapes::grid(4, 4, GridFaces::Quads);
    let err = decimate(&mut quads, &DecimateOptions::default(), Progress::none()).unwrap_err();
    assert!(
        matches!(err, Error::Unsuitable { key: Some(_), .. }),
        "{err}"
    );
    assert_eq!(quads.vertex_count(), 25);
    let mut mesh = shapes::icosphere(2);
    for target in [Target::Ratio(1.5), Target::Ratio(f64::NAN), Target::None] {
        let err = decimate(&mut mesh, &DecimateOptions::to(target), Progress::none()).unwrap_err();
        assert!(matches!(err, Error::Unsuitable { .. }), "{err}");
    }
    let missing = DecimateOptions::default().attributes(vec![AttributeWeight {
        name: "nope".into(),
        weight: 1.0,
    }]);
    assert!(decimate(&mut mesh, &missing, Progress::none()).is_err());
    assert_eq!(mesh.vertex_count(), 162);
}

fn positions(mesh: &Mesh) -> Vec<(VertexKey, V3)> {
    mesh.vertices()
        .map(|v| (v, mesh.position(v).unwrap()))
        .collect()
}

#[test]
fn a_cancelled_run_leaves_the_mesh_exactly_as_it_was() {
    let mut mesh = shapes::icosphere(4);
    let before = positions(&mesh);
    let mut calls = 0;
    let mut cb = |_: &meshloom::algo::ProgressInfo<'_>| {
        calls += 1;
        Flow::Cancel
    };
    let err = decimate(
        &mut mesh,
        &DecimateOptions::to(Target::Ratio(0.1)),
        Progress::new(&mut cb),
    )
    .unwrap_err();
    assert!(matches!(err, Error::Cancelled { .. }), "{err}");
    assert!(calls >= 1);
    assert_eq!(positions(&mesh), before);
    assert_eq!((mesh.edge_count(), mesh.face_count()), (7680, 5120));
    // With a callback that goes on, the result is the same as without one.
    let mut a = shapes::icosphere(4);
    let mut b = a.clone();
    let mut go = |_: &meshloom::algo::ProgressInfo<'_>| Flow::Continue;
    let ra = decimate(
        &mut a,
        &DecimateOptions::to(Target::Ratio(0.1)),
        Progress::new(&mut go),
    )
    .unwrap();
    let rb = decimate(
        &mut b,
        &DecimateOptions::to(Target::Ratio(0.1)),
        Progress::none(),
    )
    .unwrap();
    assert!(ra.on_copy && !rb.on_copy);
    assert_eq!(positions(&a), positions(&b));
}

/// A grid of `n × n` unit squares cut into triangles, with a corner column
/// `uv` = (x, y) / n, plus 10 on u for faces right of x = `seam` (two
/// islands, a UV seam along x = seam), and the face column `material`
/// 0 left of x = `mat`, 1 right of it.
fn seamed_grid(n: u32, seam: f64, mat: f64) -> (Mesh, HalfedgeAttr<[f64; 2]>) {
    let mut mesh = shapes::grid(n as usize, n as usize, GridFaces::Triangles);
    let uv: HalfedgeAttr<[f64; 2]> = mesh.add_halfedge_attr("uv").unwrap();
    let material = mesh.add_face_attr::<u32>("material").unwrap();
    let fs: Vec<_> = mesh.faces().collect();
    for f in fs {
        let c = mesh.face_centroid(f).unwrap();
        mesh.set_attr(&material, f, u32::from(c[0] > mat)).unwrap();
        let hs: Vec<_> = mesh.face(f).unwrap().halfedges().collect();
        for h in hs {
            let q = mesh
                .position(mesh.halfedge(h).unwrap().origin().key())
                .unwrap();
            let shift = if c[0] > seam { 10.0 } else { 0.0 };
            let value = [q[0] / f64::from(n) + shift, q[1] / f64::from(n)];
            mesh.set_attr(&uv, h, value).unwrap();
        }
    }
    (mesh, uv)
}

/// Interior edges across which the corner column `name` differs at an end.
fn seam_edges(mesh: &Mesh, name: &str) -> Vec<meshloom::EdgeKey> {
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
        .collect()
}

fn edge_ends(mesh: &Mesh, e: meshloom::EdgeKey) -> [V3; 2] {
    let h = mesh.edge(e).unwrap().halfedge(0);
    [
        mesh.position(h.origin().key()).unwrap(),
        mesh.position(h.dest().key()).unwrap(),
    ]
}

#[test]
fn a_uv_seam_stays_a_seam_in_place_and_corners_stay_on_their_island() {
    let (mut mesh, uv) = seamed_grid(24, 9.0, 100.0);
    let seams_before = seam_edges(&mesh, "uv").len();
    assert_eq!(seams_before, 24);
    let r = decimate(
        &mut mesh,
        &DecimateOptions::to(Target::Ratio(0.1)),
        Progress::none(),
    )
    .unwrap();
    mesh.validate().unwrap();
    assert_eq!(r.stopped_by, StopReason::Target, "{r:?}");
    let seams = seam_edges(&mesh, "uv");
    assert!(
        !seams.is_empty() && seams.len() <= seams_before,
        "{}",
        seams.len()
    );
    // The seam did not move: its edges lie on x = 9.
    for &e in &seams {
        for p in edge_ends(&mesh, e) {
            assert!((p[0] - 9.0).abs() < 1e-9, "seam vertex at {p:?}");
        }
    }
    // Every corner lies in its island's range, and on the face's side.
    for f in mesh.faces() {
        let c = mesh.face_centroid(f).unwrap();
        let (lo, hi) = if c[0] > 9.0 { (10.0, 11.0) } else { (0.0, 1.0) };
        for h in mesh.face(f).unwrap().halfedges() {
            let [u, v] = *mesh.attr(&uv, h).unwrap().unwrap();
            assert!(
                (lo - 1e-9..=hi + 1e-9).contains(&u),
                "u {u} in a face at x {}",
                c[0]
            );
            assert!((-1e-9..=1.0 + 1e-9).contains(&v));
        }
    }
}

#[test]
fn a_material_boundary_is_kept_where_asked() {
    let (input, _) = seamed_grid(24, 100.0, 13.0);
    let boundary = |m: &Mesh| -> Vec<meshloom::EdgeKey> {
        let mat = |f| m.attr_value("material", f).unwrap();
        m.edges()
            .filter(|&e| {
                let v = m.edge(e).unwrap();
                !v.is_boundary()
                    && mat(v.halfedge(0).face().key()) != mat(v.halfedge(1).face().key())
            })
            .collect()
    };
    let kept = DecimateOptions::to(Target::Ratio(0.1)).material(Some("material".into()));
    let mut mesh = input.clone();
    decimate(&mut mesh, &kept, Progress::none()).unwrap();
    let lines = boundary(&mesh);
    assert!(!lines.is_empty() && lines.len() <= 24);
    for &e in &lines {
        for p in edge_ends(&mesh, e) {
            assert!(
                (p[0] - 13.0).abs() < 1e-9,
                "material boundary vertex at {p:?}"
            );
        }
    }
    // Not asked: the line is free to go ragged.
    let mut free = input.clone();
    decimate(
        &mut free,
        &DecimateOptions::to(Target::Ratio(0.1)),
        Progress::none(),
    )
    .unwrap();
    let off_line = boundary(&free)
        .into_iter()
        .flat_map(|e| edge_ends(&free, e))
        .filter(|p| (p[0] - 13.0).abs() > 1e-9)
        .count();
    assert!(off_line > 0);
}

#[test]
fn spider_keeps_its_uv_seams_and_islands() {
    let mut input = read("textured/spider.obj");
    input.triangulate_all();
    // Islands: faces joined across edges that are not texcoord seams.
    let seams: std::collections::HashSet<_> = seam_edges(&input, "texcoord").into_iter().collect();
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
        if v.is_boundary() || seams.contains(&e) {
            continue;
        }
        let (a, b) = (
            index[&v.halfedge(0).face().key()],
            index[&v.halfedge(1).face().key()],
        );
        let (ra, rb) = (find(&mut parent, a), find(&mut parent, b));
        parent[ra] = rb;
    }
    let value = |m: &Mesh, h| -> Option<[f64; 2]> {
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
    };
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
            if let Some([u, v]) = value(&input, h) {
                *b = [b[0].min(u), b[1].min(v), b[2].max(u), b[3].max(v)];
            }
        }
    }
    let mut mesh = input.clone();
    let r = decimate(
        &mut mesh,
        &DecimateOptions::to(Target::Ratio(0.1)),
        Progress::none(),
    )
    .unwrap();
    mesh.validate().unwrap();
    assert!(r.collapses > 0);
    assert!(
        r.stopped_by == StopReason::Target || r.stopped_by == StopReason::NoCollapses,
        "{r:?}"
    );
    assert_eq!(mesh.hole_count(), input.hole_count());
    assert_eq!(mesh.components().count(), input.components().count());
    assert_eq!(mesh.euler_characteristic(), input.euler_characteristic());
    assert!(seam_edges(&mesh, "texcoord").len() <= seams.len());
    // Every face's corners lie together in one input island's range.
    let eps = 1e-6;
    for f in mesh.faces() {
        let corners: Vec<[f64; 2]> = mesh
            .face(f)
            .unwrap()
            .halfedges()
            .filter_map(|h| value(&mesh, h))
            .collect();
        let fits = boxes.values().any(|b| {
            corners.iter().all(|&[u, v]| {
                u >= b[0] - eps && v >= b[1] - eps && u <= b[2] + eps && v <= b[3] + eps
            })
        });
        assert!(fits, "face corners {corners:?} in no island");
    }
}

#[test]
fn a_conserved_column_keeps_its_total_and_interpolated_ones_their_range() {
    let mut mesh = shapes::icosphere(4);
    let mass = mesh
        .add_attr_with_rule::<VertexKey, f64, Conserved>("mass")
        .unwrap();
    let colour = mesh.add_vertex_attr::<[f32; 3]>("colour").unwrap();
    let vs: Vec<_> = mesh.vertices().collect();
    let mut total = 0.0;
    for (i, &v) in vs.iter().enumerate() {
        let m = 1.0 + (i % 7) as f64;
        total += m;
        mesh.set_attr(&mass, v, m).unwrap();
        let p = mesh.position(v).unwrap();
        mesh.set_attr(&colour, v, [p[0] as f32, 0.5, 1.0]).unwrap();
    }
    decimate(
        &mut mesh,
        &DecimateOptions::to(Target::Ratio(0.1)),
        Progress::none(),
    )
    .unwrap();
    let after: f64 = mesh
        .vertices()
        .map(|v| *mesh.attr(&mass, v).unwrap().unwrap())
        .sum();
    assert!(
        (after - total).abs() < 1e-9 * total,
        "{after} against {total}"
    );
    for v in mesh.vertices() {
        let c = *mesh.attr(&colour, v).unwrap().unwrap();
        assert!(
            (-1.0..=1.0).contains(&c[0]) && c[1] == 0.5 && c[2] == 1.0,
            "{c:?}"
        );
    }
}

#[test]
fn attributes_in_the_error_keep_a_curved_colour_closer() {
    // A flat grid costs nothing to decimate by position alone; a colour
    // c = x² (not linear, so interpolation loses it) only counts when named.
    let run = |weights: Vec<AttributeWeight>| -> f64 {
        let mut mesh = shapes::grid(30, 30, GridFaces::Triangles);
        let c = mesh.add_vertex_attr::<f64>("c").unwrap();
        let vs: Vec<_> = mesh.vertices().collect();
        for v in vs {
            let x = mesh.position(v).unwrap()[0] / 30.0;
            mesh.set_attr(&c, v, x * x).unwrap();
        }
        let options = DecimateOptions::to(Target::Ratio(0.2)).attributes(weights);
        decimate(&mut mesh, &options, Progress::none()).unwrap();
        // The largest deviation of the surface's colour from x², at face
        // centroids.
        mesh.faces()
            .map(|f| {
                let hs: Vec<_> = mesh
                    .face(f)
                    .unwrap()
                    .halfedges()
                    .map(|h| mesh.halfedge(h).unwrap().origin().key())
                    .collect();
                let mean_c: f64 = hs
                    .iter()
                    .map(|&v| *mesh.attr(&c, v).unwrap().unwrap())
                    .sum::<f64>()
                    / 3.0;
                let x = mesh.face_centroid(f).unwrap()[0] / 30.0;
                (mean_c - x * x).abs()
            })
            .fold(0.0, f64::max)
    };
    let plain = run(Vec::new());
    let weighted = run(vec![AttributeWeight {
        name: "c".into(),
        weight: 30.0,
    }]);
    assert!(
        weighted < plain,
        "weighted {weighted}, positions only {plain}"
    );
}

fn face_normals(mesh: &Mesh) -> Vec<V3> {
    triangles(mesh)
        .iter()
        .map(|[a, b, c]| cross(sub(*b, *a), sub(*c, *a)))
        .collect()
}

/// An icosphere with every vertex pushed in or out: bumpy, so collapses
/// turn faces.
fn bumpy_sphere() -> Mesh {
    let mut mesh = shapes::icosphere(3);
    let vs: Vec<_> = mesh.vertices().collect();
    for (i, v) in vs.into_iter().enumerate() {
        let p = mesh.position(v).unwrap();
        let s = 1.0 + 0.08 * (((i * 7919) % 13) as f64 / 12.0 - 0.5);
        mesh.set_position(v, [p[0] * s, p[1] * s, p[2] * s])
            .unwrap();
    }
    mesh
}

#[test]
fn guard_normal_deviation_refuses_flips() {
    let mut mesh = bumpy_sphere();
    let options =
        DecimateOptions::to(Target::Ratio(0.05)).max_normal_deviation(Some(20f64.to_radians()));
    let r = decimate(&mut mesh, &options, Progress::none()).unwrap();
    assert!(r.refused.normal > 0, "{r:?}");
    // No face turned inside out: every normal still points away from the
    // centre.
    for (n, t) in face_normals(&mesh).iter().zip(triangles(&mesh)) {
        assert!(dot(*n, t[0]) > 0.0);
    }
}

fn quality(t: &[V3; 3]) -> f64 {
    let n = cross(sub(t[1], t[0]), sub(t[2], t[0]));
    let s: f64 = (0..3)
        .map(|i| dot(sub(t[(i + 1) % 3], t[i]), sub(t[(i + 1) % 3], t[i])))
        .sum();
    2.0 * 3f64.sqrt() * dot(n, n).sqrt() / s
}

#[test]
fn guard_min_quality_keeps_triangles_fat() {
    let worst = |options: DecimateOptions| {
        let mut mesh = bumpy_sphere();
        let r = decimate(&mut mesh, &options, Progress::none()).unwrap();
        (triangles(&mesh).iter().map(quality).fold(1.0, f64::min), r)
    };
    let input_worst = triangles(&bumpy_sphere())
        .iter()
        .map(quality)
        .fold(1.0, f64::min);
    let (plain, _) = worst(DecimateOptions::to(Target::Ratio(0.1)));
    let (guarded, r) = worst(DecimateOptions::to(Target::Ratio(0.1)).min_quality(Some(0.4)));
    assert!(
        plain < 0.4,
        "the test needs slivers without the guard: {plain}"
    );
    assert!(guarded >= 0.4f64.min(input_worst) - 1e-12, "{guarded}");
    assert!(r.refused.quality > 0);
}

fn max_valence(mesh: &Mesh) -> usize {
    mesh.vertices()
        .map(|v| mesh.vertex(v).unwrap().degree())
        .max()
        .unwrap()
}

#[test]
fn guard_max_valence() {
    let mut plain = shapes::icosphere(4);
    decimate(
        &mut plain,
        &DecimateOptions::to(Target::Ratio(0.1)),
        Progress::none(),
    )
    .unwrap();
    assert!(max_valence(&plain) > 7, "{}", max_valence(&plain));
    let mut mesh = shapes::icosphere(4);
    let options = DecimateOptions::to(Target::Ratio(0.1)).max_valence(Some(7));
    let r = decimate(&mut mesh, &options, Progress::none()).unwrap();
    assert!(max_valence(&mesh) <= 7, "{}", max_valence(&mesh));
    assert!(r.refused.valence > 0);
}

fn boundary_vertices(mesh: &Mesh) -> Vec<(VertexKey, V3)> {
    mesh.vertices()
        .filter(|&v| mesh.vertex(v).unwrap().is_boundary())
        .map(|v| (v, mesh.position(v).unwrap()))
        .collect()
}

/// A grid with a bump in the middle, so collapses have a cost.
fn hilly_grid(n: usize) -> Mesh {
    let mut mesh = shapes::grid(n, n, GridFaces::Triangles);
    let vs: Vec<_> = mesh.vertices().collect();
    let c = n as f64 / 2.0;
    for v in vs {
        let p = mesh.position(v).unwrap();
        let r2 = ((p[0] - c).powi(2) + (p[1] - c).powi(2)) / (c * c);
        mesh.set_position(v, [p[0], p[1], 3.0 * (-3.0 * r2).exp()])
            .unwrap();
    }
    mesh
}

#[test]
fn guard_boundary_lock_and_slide() {
    let input = hilly_grid(20);
    let before = boundary_vertices(&input);
    let mut locked = input.clone();
    let options = DecimateOptions::to(Target::Ratio(0.2)).boundary(Keep::Lock);
    let r = decimate(&mut locked, &options, Progress::none()).unwrap();
    assert_eq!(boundary_vertices(&locked), before);
    assert!(r.fixed >= before.len());
    // Sliding: boundary vertices go, but every one left is on the square.
    let mut slid = input.clone();
    decimate(
        &mut slid,
        &DecimateOptions::to(Target::Ratio(0.2)),
        Progress::none(),
    )
    .unwrap();
    let after = boundary_vertices(&slid);
    assert!(after.len() < before.len());
    for (_, p) in after {
        let on = [p[0], p[1]]
            .iter()
            .any(|&x| x.abs() < 1e-9 || (x - 20.0).abs() < 1e-9);
        assert!(on, "{p:?} left the boundary");
    }
    // The four corners stay.
    for corner in [[0.0, 0.0], [20.0, 0.0], [0.0, 20.0], [20.0, 20.0]] {
        assert!(slid.vertices().any(|v| {
            let p = slid.position(v).unwrap();
            p[0] == corner[0] && p[1] == corner[1]
        }));
    }
    assert_eq!(slid.hole_count(), 1);
}

#[test]
fn guard_locked_vertex_mask() {
    let mut mesh = shapes::icosphere(3);
    let lock = mesh.add_vertex_attr::<bool>("lock").unwrap();
    let vs: Vec<_> = mesh.vertices().collect();
    let mut kept = Vec::new();
    for &v in &vs {
        if mesh.position(v).unwrap()[2] > 0.5 {
            mesh.set_attr(&lock, v, true).unwrap();
            kept.push((v, mesh.position(v).unwrap()));
        }
    }
    let options = DecimateOptions::to(Target::Ratio(0.2)).pinned(Some(lock));
    let r = decimate(&mut mesh, &options, Progress::none()).unwrap();
    assert!(r.collapses > 0);
    for (v, p) in kept {
        assert_eq!(mesh.position(v).unwrap(), p);
    }
}

#[test]
fn guard_feature_edges_by_angle_and_by_column() {
    // A grid folded along x = 10 (a 90° crease).
    let folded = || {
        let mut mesh = shapes::grid(20, 20, GridFaces::Triangles);
        let vs: Vec<_> = mesh.vertices().collect();
        for v in vs {
            let p = mesh.position(v).unwrap();
            mesh.set_position(v, [p[0], p[1], (p[0] - 10.0).abs()])
                .unwrap();
        }
        mesh
    };
    let crease = |m: &Mesh| -> Vec<(VertexKey, V3)> {
        m.vertices()
            .map(|v| (v, m.position(v).unwrap()))
            .filter(|(_, p)| (p[0] - 10.0).abs() < 1e-9)
            .collect()
    };
    let mut by_angle = folded();
    let before = crease(&by_angle);
    let options = DecimateOptions::to(Target::Ratio(0.2)).feature_angle(Some(30f64.to_radians()));
    decimate(&mut by_angle, &options, Progress::none()).unwrap();
    assert_eq!(crease(&by_angle), before);

    // The same crease marked in an edge column of a flat grid.
    let mut flat = shapes::grid(20, 20, GridFaces::Triangles);
    let feature = flat.add_edge_attr::<bool>("feature").unwrap();
    let es: Vec<_> = flat.edges().collect();
    for e in es {
        let [a, b] = edge_ends(&flat, e);
        if a[0] == 10.0 && b[0] == 10.0 {
            flat.set_attr(&feature, e, true).unwrap();
        }
    }
    let before = crease(&flat);
    let options = DecimateOptions::to(Target::Ratio(0.2)).features(Some(feature));
    decimate(&mut flat, &options, Progress::none()).unwrap();
    assert_eq!(crease(&flat), before);
}

#[test]
fn lod_levels_are_nested_valid_and_replayable() {
    let input = read("closed/cgal_sphere966.off");
    let chain = lod_chain(&input, &LodOptions::default(), Progress::none()).unwrap();
    assert_eq!(chain.levels.len(), 3);
    let n = input.vertex_count() as f64;
    let mut previous: Option<Vec<VertexKey>> = None;
    for (level, ratio) in chain.levels.iter().zip([0.5, 0.25, 0.1]) {
        let mesh = level.mesh.as_ref().unwrap();
        mesh.validate().unwrap();
        assert_eq!(mesh.vertex_count(), (ratio * n).ceil() as usize);
        assert_eq!(level.report.output.vertices, mesh.vertex_count());
        assert_eq!(mesh.euler_characteristic(), 2);
        // Nested: every vertex of a level was a vertex of the level before.
        let keys: Vec<VertexKey> = mesh.vertices().collect();
        if let Some(prev) = &previous {
            assert!(keys.iter().all(|k| prev.contains(k)));
            assert!(keys.len() < prev.len());
        }
        // Replaying the record's prefix gives the same mesh.
        let mut again = input.clone();
        replay(&mut again, &chain.record[..level.collapses]).unwrap();
        assert_eq!(positions(&again), positions(mesh));
        previous = Some(keys);
    }
    assert_eq!(chain.record.len(), chain.levels[2].collapses);
    // Targets out of order are refused.
    let bad = LodOptions::default().targets(vec![Target::Ratio(0.1), Target::Ratio(0.5)]);
    assert!(matches!(
        lod_chain(&input, &bad, Progress::none()),
        Err(Error::Unsuitable { .. })
    ));
    // A record replayed on another mesh fails and changes nothing.
    let mut other = shapes::icosphere(1);
    let before = positions(&other);
    assert!(replay(&mut other, &chain.record).is_err());
    assert_eq!(positions(&other), before);
}
