//! Requests whose results would exhaust memory, and arithmetic that would
//! leave `f64` or `f32`: refused before any work (or before anything is
//! written), with the estimate or the element in the message, and the
//! mesh unchanged.

use meshloom::algo::remesh::{remesh, RemeshOptions, Sizing};
use meshloom::algo::{
    catmull_clark, loop_subdivide, midpoint_subdivide, sqrt3_subdivide, MidpointOptions, Progress,
    SubdivisionOptions,
};
use meshloom::io::{write_stl, StlEncoding};
use meshloom::{shapes, Error, Mesh};

mod common;
use common::snapshot;

fn repro(name: &str) -> String {
    format!(
        "{}/../shared/data/repros/{name}",
        env!("CARGO_MANIFEST_DIR")
    )
}

/// Eight levels of every scheme on a 634-triangle closed mesh (about 41M
/// faces at 4⁸: the CLI was killed for memory) are refused up front.
#[test]
fn subdivision_past_max_faces_is_refused_with_its_estimate() {
    let base = shapes::icosphere(3);
    let faces = base.face_count() as u64;
    let opts = SubdivisionOptions::default().levels(8);
    type Scheme = fn(
        &mut Mesh,
        &SubdivisionOptions,
        Progress<'_>,
    ) -> meshloom::Result<meshloom::algo::SubdivisionReport>;
    let schemes: [(Scheme, u64); 3] = [
        (loop_subdivide, faces * 4u64.pow(8)),
        (catmull_clark, 3 * faces * 4u64.pow(7)),
        (sqrt3_subdivide, faces * 3u64.pow(8) * 4 / 3),
    ];
    for (run, expected) in schemes {
        let mut m = base.clone();
        match run(&mut m, &opts, Progress::none()) {
            Err(Error::TooLarge {
                estimate,
                limit,
                option,
                ..
            }) => {
                assert_eq!(estimate, expected);
                assert_eq!(limit, 10_000_000);
                assert_eq!(option, "max_faces");
            }
            other => panic!("expected TooLarge, got {other:?}"),
        }
        assert_eq!(m.face_count(), base.face_count());
    }
    // Midpoint too, and a raised limit lets a level through.
    let mut m = base.clone();
    let err = midpoint_subdivide(
        &mut m,
        &MidpointOptions::default().levels(9),
        Progress::none(),
    );
    assert!(matches!(err, Err(Error::TooLarge { .. })), "{err:?}");
    let opts = SubdivisionOptions::default()
        .levels(1)
        .max_faces(4 * base.face_count());
    loop_subdivide(&mut m, &opts, Progress::none()).unwrap();
    assert_eq!(m.face_count(), 4 * base.face_count());
    let opts = SubdivisionOptions::default()
        .levels(1)
        .max_faces(4 * m.face_count() - 1);
    assert!(loop_subdivide(&mut m, &opts, Progress::none()).is_err());
}

/// A target edge length of 1e-6 on a unit cube asks for about 10¹³
/// triangles: refused with the estimate.
#[test]
fn remeshing_to_a_tiny_length_is_refused_with_its_estimate() {
    let mut m = shapes::cube();
    m.triangulate_all();
    let before = snapshot(&m);
    for l in [1e-6, 1e-12] {
        let opts = RemeshOptions::default().sizing(Sizing::Uniform(l));
        match remesh(&mut m, &opts, Progress::none()) {
            Err(Error::TooLarge { estimate, .. }) => {
                // 6 unit squares over equilateral triangles of side l
                // (past u64, the estimate saturates).
                let expected = (6.0 / (3f64.sqrt() / 4.0 * l * l)).min(u64::MAX as f64);
                assert!(
                    (estimate as f64 / expected - 1.0).abs() < 1e-6,
                    "{estimate}"
                );
            }
            other => panic!("expected TooLarge, got {other:?}"),
        }
        assert_eq!(snapshot(&m), before);
    }
    // The default (the mean edge length) runs.
    remesh(&mut m, &RemeshOptions::default(), Progress::none()).unwrap();
}

/// Coordinates near ±1.7e308: the subdivision's sums overflow. The
/// result is refused, naming the vertex, and the mesh is unchanged.
#[test]
fn subdivision_that_overflows_f64_is_refused() {
    let m = meshloom::io::read(repro("bigmax.obj")).unwrap();
    let mut work = m.clone();
    let r = catmull_clark(&mut work, &SubdivisionOptions::default(), Progress::none());
    assert!(matches!(r, Err(Error::NonFiniteResult { .. })), "{r:?}");
    assert_eq!(snapshot(&work), snapshot(&m));
    // Loop's stencils stay in range here: its result is finite.
    let mut work = m.clone();
    loop_subdivide(&mut work, &SubdivisionOptions::default(), Progress::none()).unwrap();
    assert!(work
        .vertices()
        .all(|v| work.position(v).unwrap().iter().all(|c| c.is_finite())));
}

/// STL holds `f32`: a coordinate of 1e300 would be written as infinity
/// and 1e-300 as zero. Both are refused, naming the vertex.
#[test]
fn stl_refuses_positions_that_f32_cannot_hold() {
    for (name, what) in [("big1e300.obj", "1e300"), ("tiny1e-300.obj", "1e-300")] {
        let m = meshloom::io::read(repro(name)).unwrap();
        for encoding in [StlEncoding::Binary, StlEncoding::Ascii] {
            let mut out = Vec::new();
            let err = write_stl(&m, &mut out, encoding).unwrap_err();
            let text = err.to_string();
            assert!(
                text.contains("vertex") && text.contains("32-bit"),
                "{what}: {text}"
            );
            assert!(out.is_empty());
        }
    }
}

/// STL output cuts a concave polygon as `triangulate` does (the fan it
/// wrote before left the polygon), and the triangles cover its area.
#[test]
fn stl_cuts_concave_polygons_inside_their_outline() {
    let p = [
        [0.0, 0.0, 0.0],
        [2.0, 0.0, 0.0],
        [2.0, 2.0, 0.0],
        [1.0, 0.5, 0.0],
        [0.0, 2.0, 0.0],
    ];
    // The loop starts at (2, 2), which does not see (0, 2) past the notch
    // at (1, 0.5): the fan it began with made an inverted triangle there.
    let m = Mesh::from_polygons(&p, &[[2u32, 3, 4, 0, 1]]).unwrap();
    let mut out = Vec::new();
    write_stl(&m, &mut out, StlEncoding::Binary).unwrap();
    let back = meshloom::io::read_stl(&out[..]).unwrap();
    let areas: Vec<f64> = back
        .faces()
        .map(|f| {
            let v: Vec<[f64; 3]> = back
                .face(f)
                .unwrap()
                .vertices()
                .map(|v| back.position(v).unwrap())
                .collect();
            let (a, b, c) = (v[0], v[1], v[2]);
            0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))
        })
        .collect();
    // Every triangle inside (none inverted), together the shoelace area.
    assert!(areas.iter().all(|&a| a > 0.0), "{areas:?}");
    assert!((areas.iter().sum::<f64>() - 2.5).abs() < 1e-6, "{areas:?}");
    assert_eq!(back.face_count(), 3);
}
