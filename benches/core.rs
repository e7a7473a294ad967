//! Criterion benches of the core: building from compact buffers, one-ring
//! circulation, face loops and whole-mesh traversals.
//!
//! Run with `cargo bench --bench core`. Sample counts are kept small (10
//! samples, 2 s measurement) so the whole run takes a couple of minutes on a
//! 2-core machine.

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, Criterion};
use meshloom::shapes::{self, GridFaces};
use meshloom::{traverse, Mesh};

fn config() -> Criterion {
    Criterion::default()
        .sample_size(10)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2))
}

fn build(c: &mut Criterion) {
    let mut group = c.benchmark_group("build");
    // 250,000 vertices, 498,002 triangles, one boundary loop.
    let grid = shapes::grid_polygons(499, 499, GridFaces::Triangles);
    group.bench_function("grid_499x499_triangles", |b| {
        b.iter(|| Mesh::from_buffers(black_box(&grid)).expect("valid"))
    });
    // 163,842 vertices, 327,680 triangles, closed.
    let ico = shapes::icosphere_polygons(7);
    group.bench_function("icosphere_7", |b| {
        b.iter(|| Mesh::from_buffers(black_box(&ico)).expect("valid"))
    });
    let mesh = Mesh::from_buffers(&ico).expect("valid");
    group.bench_function("icosphere_7_to_polygons", |b| {
        b.iter(|| black_box(&mesh).to_polygons())
    });
    group.finish();
}

fn circulate(c: &mut Criterion) {
    let mut group = c.benchmark_group("circulate");
    for (name, mesh) in [
        ("icosphere_7", shapes::icosphere(7)),
        (
            "grid_499x499_triangles",
            shapes::grid(499, 499, GridFaces::Triangles),
        ),
    ] {
        group.bench_function(format!("one_ring_index_sum/{name}"), |b| {
            b.iter(|| {
                let m = black_box(&mesh);
                let mut sum = 0usize;
                for v in m.vertices() {
                    for w in m.vertex(v).expect("live").neighbors() {
                        sum += w.index();
                    }
                }
                sum
            })
        });
        group.bench_function(format!("face_loops/{name}"), |b| {
            b.iter(|| {
                let m = black_box(&mesh);
                let mut sum = 0usize;
                for f in m.faces() {
                    for v in m.face(f).expect("live").vertices() {
                        sum += v.index();
                    }
                }
                sum
            })
        });
    }
    group.finish();
}

fn traversals(c: &mut Criterion) {
    let mut group = c.benchmark_group("traverse");
    let mesh = shapes::icosphere(7);
    let start = mesh.vertices().next().expect("non-empty");
    group.bench_function("bfs_vertices/icosphere_7", |b| {
        b.iter(|| mesh.bfs_vertices(start).expect("live").count())
    });
    group.bench_function("components/icosphere_7", |b| {
        b.iter(|| traverse::components(black_box(&mesh)).count())
    });
    group.finish();
}

criterion_group! {
    name = benches;
    config = config();
    targets = build, circulate, traversals
}
criterion_main!(benches);
