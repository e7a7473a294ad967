//! One report vocabulary: every report that changes the mesh's elements
//! says so in `input` and `output` [`Counts`] (the counts before and after,
//! checked here against the mesh), every report of moved vertices names
//! them `moved` and the vertices kept in place `fixed`, with
//! `max_displacement`, and a subdivision names its `scheme` by [`Scheme`].

use meshloom::algo::decimate::{decimate, DecimateOptions, Target};
use meshloom::algo::fill_hole::{fill_holes, FillHoleOptions};
use meshloom::algo::remesh::{remesh, RemeshOptions, Sizing};
use meshloom::algo::smooth::{smooth, SmoothOptions};
use meshloom::algo::{subdivide, Counts, Keep, Progress, Scheme, SubdivisionOptions};
use meshloom::shapes::{self, GridFaces};
use meshloom::Mesh;

/// A grid with its inner vertices lifted in a bump (so smoothing and
/// fairing move them).
fn bumpy_grid() -> Mesh {
    let mut mesh = shapes::grid(8, 8, GridFaces::Triangles);
    for p in mesh.position_slots_mut().unwrap() {
        p[2] = (p[0] * 0.7).sin() * (p[1] * 0.9).sin();
    }
    mesh
}

fn boundary_vertices(mesh: &Mesh) -> usize {
    mesh.vertices()
        .filter(|&v| mesh.vertex(v).unwrap().is_boundary())
        .count()
}

#[test]
fn decimate_reports_input_output_and_fixed() {
    let mut mesh = bumpy_grid();
    let before = Counts::of(&mesh);
    let options = DecimateOptions::default()
        .target(Target::Ratio(0.5))
        .boundary(Keep::Lock);
    let r = decimate(&mut mesh, &options, Progress::none()).unwrap();
    assert_eq!(r.input, before);
    assert_eq!(r.output, Counts::of(&mesh));
    assert_ne!(r.input, r.output);
    assert_eq!(
        r.fixed,
        boundary_vertices(&shapes::grid(8, 8, GridFaces::Triangles))
    );
}

#[test]
fn remesh_reports_input_output_and_fixed() {
    let mut mesh = bumpy_grid();
    let before = Counts::of(&mesh);
    let options = RemeshOptions::default()
        .sizing(Sizing::Uniform(0.5))
        .iterations(2)
        .boundary(Keep::Lock);
    let r = remesh(&mut mesh, &options, Progress::none()).unwrap();
    assert_eq!(r.input, before);
    assert_eq!(r.output, Counts::of(&mesh));
    assert_ne!(r.input, r.output);
    assert!(r.fixed >= boundary_vertices(&bumpy_grid()), "{}", r.fixed);
}

#[test]
fn subdivision_reports_its_scheme_and_input_output_per_level() {
    let mut mesh = bumpy_grid();
    let before = Counts::of(&mesh);
    let options = SubdivisionOptions::default().levels(2);
    let r = subdivide(&mut mesh, Scheme::Loop, &options, Progress::none()).unwrap();
    assert_eq!(r.scheme, Scheme::Loop);
    assert_eq!(r.input, before);
    assert_eq!(r.output, Counts::of(&mesh));
    assert_eq!(r.levels.len(), 2);
    assert_eq!(r.levels[1].output, r.output);
    assert_eq!(r.levels[0].output.faces * 4, r.output.faces);
    // No level: the output is the input.
    let mut same = bumpy_grid();
    let none = SubdivisionOptions::default().levels(0);
    let r = subdivide(&mut same, Scheme::Loop, &none, Progress::none()).unwrap();
    assert_eq!(r.output, r.input);
}

#[test]
fn fill_holes_reports_input_and_output() {
    let mut mesh = shapes::icosphere(2);
    let faces: Vec<_> = mesh.faces().step_by(50).collect();
    for f in faces {
        mesh.remove_face(f).unwrap();
    }
    let before = Counts::of(&mesh);
    assert!(before.holes > 0);
    let r = fill_holes(&mut mesh, &FillHoleOptions::default(), Progress::none()).unwrap();
    assert_eq!(r.input, before);
    assert_eq!(r.output, Counts::of(&mesh));
    assert_eq!(r.output.holes, 0);
    assert_eq!(r.output.faces, r.input.faces + r.faces_added);
    assert_eq!(r.output.vertices, r.input.vertices + r.vertices_added);
}

#[test]
fn smooth_reports_moved_and_fixed() {
    let mut mesh = bumpy_grid();
    let n = mesh.vertex_count();
    let boundary = boundary_vertices(&mesh);
    let options = SmoothOptions::default().boundary(Keep::Lock);
    let r = smooth(&mut mesh, &options, Progress::none()).unwrap();
    assert_eq!(r.fixed, boundary);
    assert_eq!(r.moved, n - boundary);
    assert!(r.max_displacement > 0.0);
}

#[cfg(feature = "sparse")]
#[test]
fn fair_reports_moved_and_fixed() {
    use meshloom::algo::fair::{fair, FairOptions};
    let mut mesh = bumpy_grid();
    let n = mesh.vertex_count();
    // Order 1: only the boundary is fixed.
    let options = FairOptions::default().order(1);
    let r = fair(&mut mesh, &options, Progress::none()).unwrap();
    let boundary = boundary_vertices(&mesh);
    assert_eq!(r.moved, n - boundary);
    // The boundary vertices with an inner neighbour: all but the grid
    // corners whose neighbours are all on the boundary.
    assert!(r.fixed > 0 && r.fixed <= boundary, "{}", r.fixed);
    assert!(boundary - r.fixed <= 4, "{}", r.fixed);
    assert!(r.max_displacement > 0.0);
}
