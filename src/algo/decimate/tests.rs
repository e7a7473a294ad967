//! Unit tests of the decimator's internals; the behaviour tests are in
//! `tests/decimate.rs`.

use super::*;
use crate::algo::Progress;
use crate::shapes;

#[test]
fn a_flat_grid_decimates_for_free() {
    let mut mesh = shapes::grid(20, 20, shapes::GridFaces::Triangles);
    let r = decimate(
        &mut mesh,
        &DecimateOptions::to(Target::Vertices(60)),
        Progress::none(),
    )
    .unwrap();
    assert_eq!(r.stopped_by, StopReason::Target);
    assert_eq!(mesh.vertex_count(), 60);
    assert!(r.error < 1e-9, "{r:?}");
    mesh.validate().unwrap();
}
