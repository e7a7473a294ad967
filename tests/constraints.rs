//! One meaning for the constraint words in every algorithm (issue 25): on
//! an open, noisy grid, decimate, remesh, smooth and fair with the boundary
//! locked leave every boundary vertex bit for bit (and the boundary edges
//! as they were); with the boundary sliding they keep every boundary vertex
//! on the input's boundary polyline (within 1e-9 of the bounding box's
//! diagonal); with it free, smoothing moves boundary vertices off it; and
//! pinned vertices stay bit for bit in all four.
//! (Fairing needs the `sparse` feature, on by default.)

use meshloom::algo::decimate::{decimate, DecimateOptions, Target};
use meshloom::algo::remesh::{remesh, RemeshOptions};
use meshloom::algo::smooth::{smooth, SmoothMethod, SmoothOptions};
use meshloom::algo::{Keep, Progress};
use meshloom::attr::VertexAttr;
use meshloom::shapes::{self, GridFaces};
use meshloom::{Mesh, VertexKey};

type V3 = [f64; 3];

/// A deterministic stream of numbers in [-1, 1) (a 64-bit LCG).
struct Noise(u64);

impl Noise {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (self.0 >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }
}

/// A 20 × 20 triangle grid (cells of 1) whose interior vertices are
/// jittered by up to ±0.25 in x and y and ±0.3 in z; with `bent`, the
/// boundary vertices too, by ±0.05 in z (a zigzag polyline that turns by
/// less than the 45° that makes a corner).
fn noisy_grid(bent: bool) -> Mesh {
    let mut mesh = shapes::grid(20, 20, GridFaces::Triangles);
    let mut noise = Noise(25);
    let keys: Vec<VertexKey> = mesh.vertices().collect();
    for v in keys {
        let p = mesh.position(v).unwrap();
        let (a, b, c) = (noise.next(), noise.next(), noise.next());
        let q = if mesh.vertex(v).unwrap().is_boundary() {
            let corner = (p[0] == 0.0 || p[0] == 20.0) && (p[1] == 0.0 || p[1] == 20.0);
            let dz = if bent && !corner { 0.05 * c } else { 0.0 };
            [p[0], p[1], p[2] + dz]
        } else {
            [p[0] + 0.25 * a, p[1] + 0.25 * b, p[2] + 0.3 * c]
        };
        mesh.set_position(v, q).unwrap();
    }
    mesh
}

fn bits(p: V3) -> [u64; 3] {
    p.map(f64::to_bits)
}

/// The boundary vertices with their positions' bits, by key.
fn boundary(mesh: &Mesh) -> Vec<(VertexKey, [u64; 3])> {
    let mut out: Vec<_> = mesh
        .vertices()
        .filter(|&v| mesh.vertex(v).unwrap().is_boundary())
        .map(|v| (v, bits(mesh.position(v).unwrap())))
        .collect();
    out.sort();
    out
}

fn boundary_edges(mesh: &Mesh) -> usize {
    mesh.edges()
        .filter(|&e| mesh.edge(e).unwrap().is_boundary())
        .count()
}

/// The boundary polyline: one segment per boundary edge.
fn polyline(mesh: &Mesh) -> Vec<(V3, V3)> {
    mesh.edges()
        .filter(|&e| mesh.edge(e).unwrap().is_boundary())
        .map(|e| {
            let [a, b] = mesh.edge(e).unwrap().vertices();
            (mesh.position(a).unwrap(), mesh.position(b).unwrap())
        })
        .collect()
}

fn distance_to(segments: &[(V3, V3)], p: V3) -> f64 {
    let sub = |a: V3, b: V3| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let dot = |a: V3, b: V3| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    segments
        .iter()
        .map(|&(a, b)| {
            let d = sub(b, a);
            let t = (dot(sub(p, a), d) / dot(d, d)).clamp(0.0, 1.0);
            let e = sub(p, [a[0] + t * d[0], a[1] + t * d[1], a[2] + t * d[2]]);
            dot(e, e).sqrt()
        })
        .fold(f64::INFINITY, f64::min)
}

fn diagonal(mesh: &Mesh) -> f64 {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for v in mesh.vertices() {
        let p = mesh.position(v).unwrap();
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    (0..3).map(|k| (hi[k] - lo[k]).powi(2)).sum::<f64>().sqrt()
}

/// The algorithms under test.
#[derive(Copy, Clone, Debug)]
enum Algorithm {
    Decimate,
    Remesh,
    Smooth(SmoothMethod),
    #[cfg(feature = "sparse")]
    Fair,
}

fn algorithms() -> Vec<Algorithm> {
    let mut out = vec![
        Algorithm::Decimate,
        Algorithm::Remesh,
        Algorithm::Smooth(SmoothMethod::Uniform),
        Algorithm::Smooth(SmoothMethod::Cotan),
        Algorithm::Smooth(SmoothMethod::Taubin),
    ];
    #[cfg(feature = "sparse")]
    out.extend([Algorithm::Smooth(SmoothMethod::Implicit), Algorithm::Fair]);
    out
}

/// Run `algorithm` on `mesh` with this boundary rule and pinned column.
fn run(algorithm: Algorithm, mesh: &mut Mesh, boundary: Keep, pinned: Option<VertexAttr<bool>>) {
    match algorithm {
        Algorithm::Decimate => {
            let o = DecimateOptions::to(Target::Ratio(0.3))
                .boundary(boundary)
                .pinned(pinned);
            decimate(mesh, &o, Progress::none()).unwrap();
        }
        Algorithm::Remesh => {
            let o = RemeshOptions::default()
                .boundary(boundary)
                .pinned(pinned)
                .iterations(5);
            remesh(mesh, &o, Progress::none()).unwrap();
        }
        Algorithm::Smooth(method) => {
            let o = SmoothOptions::with_method(method)
                .boundary(boundary)
                .pinned(pinned)
                .step((method == SmoothMethod::Implicit).then_some(0.1));
            smooth(mesh, &o, Progress::none()).unwrap();
        }
        #[cfg(feature = "sparse")]
        Algorithm::Fair => {
            use meshloom::algo::fair::{fair, FairOptions};
            let o = FairOptions::default().boundary(boundary).pinned(pinned);
            fair(mesh, &o, Progress::none()).unwrap();
        }
    }
    mesh.validate().unwrap();
}

#[test]
fn lock_leaves_every_boundary_vertex_and_edge_as_it_was() {
    for bent in [false, true] {
        let input = noisy_grid(bent);
        for a in algorithms() {
            let mut mesh = input.clone();
            run(a, &mut mesh, Keep::Lock, None);
            assert_eq!(boundary(&mesh), boundary(&input), "{a:?}, bent {bent}");
            assert_eq!(boundary_edges(&mesh), boundary_edges(&input), "{a:?}");
            assert_eq!(mesh.hole_count(), 1, "{a:?}");
        }
    }
}

#[test]
fn slide_keeps_every_boundary_vertex_on_the_input_boundary() {
    for bent in [false, true] {
        let input = noisy_grid(bent);
        let line = polyline(&input);
        let tolerance = 1e-9 * diagonal(&input);
        for a in algorithms() {
            let mut mesh = input.clone();
            run(a, &mut mesh, Keep::Slide, None);
            let after = boundary(&mesh);
            for &(v, p) in &after {
                let d = distance_to(&line, p.map(f64::from_bits));
                assert!(d <= tolerance, "{a:?}, bent {bent}: {v:?} is {d} off");
            }
            assert_eq!(mesh.hole_count(), 1, "{a:?}");
            // Sliding is not locking: the boundary changed.
            match a {
                Algorithm::Decimate => assert!(after.len() < boundary(&input).len(), "{a:?}"),
                Algorithm::Smooth(_) | Algorithm::Remesh => {
                    assert_ne!(after, boundary(&input), "{a:?}, bent {bent}")
                }
                #[cfg(feature = "sparse")]
                Algorithm::Fair => {}
            }
        }
    }
}

#[test]
fn free_lets_smoothing_move_boundary_vertices_off_the_boundary() {
    let input = noisy_grid(false);
    let line = polyline(&input);
    let tolerance = 1e-9 * diagonal(&input);
    for method in [
        SmoothMethod::Uniform,
        SmoothMethod::Cotan,
        SmoothMethod::Taubin,
    ] {
        let mut mesh = input.clone();
        run(Algorithm::Smooth(method), &mut mesh, Keep::Free, None);
        let off = input
            .vertices()
            .filter(|&v| input.vertex(v).unwrap().is_boundary())
            .filter(|&v| distance_to(&line, mesh.position(v).unwrap()) > tolerance)
            .count();
        assert!(
            off > 0,
            "{method:?}: no boundary vertex moved off the boundary"
        );
    }
}

#[test]
fn pinned_vertices_stay_bit_for_bit() {
    for boundary_rule in [Keep::Lock, Keep::Slide] {
        for a in algorithms() {
            let mut mesh = noisy_grid(true);
            let pinned = mesh.add_vertex_attr::<bool>("pinned").unwrap();
            let keys: Vec<VertexKey> = mesh.vertices().collect();
            let mut kept = Vec::new();
            for (i, &v) in keys.iter().enumerate() {
                if i % 7 == 3 {
                    mesh.set_attr(&pinned, v, true).unwrap();
                    kept.push((v, bits(mesh.position(v).unwrap())));
                }
            }
            run(a, &mut mesh, boundary_rule, Some(pinned));
            for &(v, p) in &kept {
                let q = mesh.position(v).map(bits);
                assert_eq!(q.ok(), Some(p), "{a:?}, {boundary_rule}: {v:?}");
            }
        }
    }
}

#[cfg(feature = "sparse")]
#[test]
fn fair_with_a_free_boundary_moves_it_and_keeps_the_pins() {
    use meshloom::algo::fair::{fair, FairOptions};
    let input = noisy_grid(false);
    // Nothing holds a free boundary: refused, the mesh unchanged.
    let mut mesh = input.clone();
    let free = FairOptions::default().boundary(Keep::Free);
    assert!(fair(&mut mesh, &free, Progress::none()).is_err());
    assert_eq!(boundary(&mesh), boundary(&input));
    // Pinned interior vertices hold it.
    let pinned = mesh.add_vertex_attr::<bool>("pinned").unwrap();
    let keys: Vec<VertexKey> = mesh.vertices().collect();
    for &v in &keys {
        let p = mesh.position(v).unwrap();
        let ring = (p[0] - 10.0).abs().max((p[1] - 10.0).abs());
        if (3.0..4.0).contains(&ring) {
            mesh.set_attr(&pinned, v, true).unwrap();
        }
    }
    let o = free.pinned(Some(pinned.clone()));
    fair(&mut mesh, &o, Progress::none()).unwrap();
    assert_ne!(boundary(&mesh), boundary(&input));
    for &v in &keys {
        if mesh.attr(&pinned, v).unwrap() == Some(&true) {
            assert_eq!(
                bits(mesh.position(v).unwrap()),
                bits(input.position(v).unwrap())
            );
        }
    }
}
