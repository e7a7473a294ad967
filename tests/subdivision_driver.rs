//! `subdivide` as the one entry point: every scheme through it gives what
//! its own function gives, the option words, the checks every scheme
//! shares (a crease column only where the scheme takes one).

mod common;

use common::snapshot;
use meshloom::algo::subdivision::MidpointFaces;
use meshloom::algo::{
    catmull_clark, loop_subdivide, midpoint_subdivide, sqrt3_subdivide, subdivide, Boundary,
    MidpointOptions, Progress, Scheme, SubdivisionOptions, SubdivisionReport, VertexInterpolation,
};
use meshloom::{EdgeKey, Error, Mesh};

type Run = fn(&mut Mesh, &SubdivisionOptions, Progress<'_>) -> meshloom::Result<SubdivisionReport>;

fn midpoint(
    m: &mut Mesh,
    o: &SubdivisionOptions,
    p: Progress<'_>,
) -> meshloom::Result<SubdivisionReport> {
    let o = MidpointOptions::default()
        .levels(o.levels)
        .faces(o.midpoint_faces)
        .max_faces(o.max_faces);
    midpoint_subdivide(m, &o, p)
}

/// Every position, in vertex order, as bits.
fn position_bits(m: &Mesh) -> Vec<[u64; 3]> {
    m.vertices()
        .map(|v| m.position(v).unwrap().map(f64::to_bits))
        .collect()
}

/// An icosphere with a hole, a sharpness column and a pinned vertex.
fn open_sphere() -> Mesh {
    let mut m = meshloom::shapes::icosphere(2);
    let f = m.faces().nth(7).unwrap();
    m.remove_face(f).unwrap();
    let crease = m.add_edge_attr::<f64>("crease").unwrap();
    let edges: Vec<EdgeKey> = m.edges().collect();
    for (i, &e) in edges.iter().enumerate().step_by(5) {
        m.set_attr(&crease, e, 0.5 + (i % 3) as f64).unwrap();
    }
    let pin = m.add_vertex_attr::<bool>("pin").unwrap();
    let v = m.vertices().nth(3).unwrap();
    m.set_attr(&pin, v, true).unwrap();
    m
}

#[test]
fn every_scheme_through_subdivide_is_its_own_function() {
    let creases = SubdivisionOptions::default()
        .levels(2)
        .crease_column(Some("crease".into()))
        .corner_column(Some("pin".into()));
    let plain = SubdivisionOptions::default()
        .levels(2)
        .boundary(Boundary::CreaseAndCorners)
        .corner_column(Some("pin".into()));
    let quads = SubdivisionOptions::default()
        .levels(2)
        .midpoint_faces(MidpointFaces::Quads);
    let cases: [(Scheme, Run, &SubdivisionOptions); 5] = [
        (Scheme::Loop, loop_subdivide, &creases),
        (Scheme::CatmullClark, catmull_clark, &creases),
        (Scheme::Sqrt3, sqrt3_subdivide, &plain),
        (Scheme::Midpoint, midpoint, &plain),
        (Scheme::Midpoint, midpoint, &quads),
    ];
    for (scheme, run, options) in cases {
        let mut a = open_sphere();
        let mut b = a.clone();
        let ra = subdivide(&mut a, scheme, options, Progress::none()).unwrap();
        let rb = run(&mut b, options, Progress::none()).unwrap();
        assert_eq!(ra, rb, "{scheme}");
        assert_eq!(ra.scheme, scheme);
        assert_eq!(ra.levels.len(), 2);
        assert_eq!(position_bits(&a), position_bits(&b), "{scheme}");
        assert_eq!(snapshot(&a), snapshot(&b), "{scheme}");
        a.validate().unwrap();
    }
}

#[test]
fn option_enums_take_their_words() {
    for word in Scheme::WORDS {
        assert_eq!(word.parse::<Scheme>().unwrap().to_string(), *word);
    }
    assert_eq!(
        "crease_and_corners".parse::<Boundary>().unwrap(),
        Boundary::CreaseAndCorners
    );
    assert_eq!(Boundary::WORDS, ["crease", "crease-and-corners"]);
    assert_eq!(
        "linear".parse::<VertexInterpolation>().unwrap(),
        VertexInterpolation::Linear
    );
    assert_eq!(VertexInterpolation::Smooth.to_string(), "smooth");
    assert_eq!(MidpointFaces::WORDS, ["auto", "quads", "triangles"]);
    assert_eq!(
        "Quads".parse::<MidpointFaces>().unwrap(),
        MidpointFaces::Quads
    );
    let err = "loops".parse::<Scheme>().unwrap_err();
    assert_eq!(err.option, "Scheme");
    assert!(err
        .to_string()
        .contains("loop, catmull-clark, sqrt3, midpoint"));
}

/// √3 and midpoint refuse a crease column (even a missing one: the scheme
/// is what is wrong), before any work, and leave the mesh as it was; Loop
/// and Catmull-Clark check that it exists.
#[test]
fn a_crease_column_is_refused_where_the_scheme_takes_none() {
    for scheme in [Scheme::Sqrt3, Scheme::Midpoint] {
        assert!(!scheme.takes_creases());
        for column in ["crease", "missing"] {
            let mut m = open_sphere();
            let before = snapshot(&m);
            let options = SubdivisionOptions::default().crease_column(Some(column.into()));
            let err = subdivide(&mut m, scheme, &options, Progress::none()).unwrap_err();
            match &err {
                Error::Unsuitable {
                    algorithm, reason, ..
                } => {
                    assert_eq!(*algorithm, format!("{scheme}_subdivide"));
                    assert!(reason.contains("crease"), "{reason}");
                }
                other => panic!("{scheme}: {other}"),
            }
            assert_eq!(snapshot(&m), before);
        }
    }
    for scheme in [Scheme::Loop, Scheme::CatmullClark] {
        assert!(scheme.takes_creases());
        let mut m = open_sphere();
        let options = SubdivisionOptions::default().crease_column(Some("missing".into()));
        let err = subdivide(&mut m, scheme, &options, Progress::none()).unwrap_err();
        assert!(matches!(err, Error::AttributeMissing { .. }), "{err}");
    }
}

/// Midpoint through the driver: the faces option, and the columns named in
/// the options are checked as for every scheme.
#[test]
fn midpoint_through_the_driver() {
    let mut m = meshloom::shapes::icosahedron();
    let options = SubdivisionOptions::default().midpoint_faces(MidpointFaces::Quads);
    let r = subdivide(&mut m, Scheme::Midpoint, &options, Progress::none()).unwrap();
    assert_eq!(r.scheme, Scheme::Midpoint);
    assert_eq!((m.vertex_count(), m.face_count()), (12 + 30 + 20, 60));
    m.validate().unwrap();
    let options = SubdivisionOptions::default().corner_column(Some("missing".into()));
    let err = subdivide(&mut m, Scheme::Midpoint, &options, Progress::none()).unwrap_err();
    assert!(matches!(err, Error::AttributeMissing { .. }), "{err}");
}
