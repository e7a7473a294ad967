//! The symmetric Hausdorff distance between two triangle meshes by point
//! sampling, relative to the input's bounding-box diagonal: the one
//! measure of "the surface is kept" for the decimation and remeshing
//! tests.

use meshloom::Mesh;

/// A point or vector.
pub type V3 = [f64; 3];

fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Where the samples of each side are taken.
#[derive(Clone, Copy, Debug)]
pub enum Sampling {
    /// Every triangle's corners, edge midpoints and centroid (fine; for
    /// small outputs such as decimated meshes).
    Dense,
    /// The vertices and the face centroids, thinned to at most this many
    /// points by taking every k-th (fast on large meshes).
    Capped(usize),
}

/// The corner positions of every face (triangles; a polygon's first
/// three corners).
pub fn triangles(mesh: &Mesh) -> Vec<[V3; 3]> {
    mesh.faces()
        .map(|f| {
            let vs: Vec<V3> = mesh
                .face(f)
                .unwrap()
                .vertices()
                .map(|v| mesh.position(v).unwrap())
                .collect();
            [vs[0], vs[1], vs[2]]
        })
        .collect()
}

/// Distance from `p` to the triangle `t` (Ericson's closest point).
pub fn point_triangle(p: V3, t: &[V3; 3]) -> f64 {
    let [a, b, c] = *t;
    let (ab, ac, ap) = (sub(b, a), sub(c, a), sub(p, a));
    let (d1, d2) = (dot(ab, ap), dot(ac, ap));
    let at = |q: V3| dot(sub(p, q), sub(p, q)).sqrt();
    let lerp = |x: V3, y: V3, s: f64| {
        [
            x[0] + s * (y[0] - x[0]),
            x[1] + s * (y[1] - x[1]),
            x[2] + s * (y[2] - x[2]),
        ]
    };
    if d1 <= 0.0 && d2 <= 0.0 {
        return at(a);
    }
    let bp = sub(p, b);
    let (d3, d4) = (dot(ab, bp), dot(ac, bp));
    if d3 >= 0.0 && d4 <= d3 {
        return at(b);
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return at(lerp(a, b, d1 / (d1 - d3)));
    }
    let cp = sub(p, c);
    let (d5, d6) = (dot(ab, cp), dot(ac, cp));
    if d6 >= 0.0 && d5 <= d6 {
        return at(c);
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return at(lerp(a, c, d2 / (d2 - d6)));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0 {
        return at(lerp(b, c, (d4 - d3) / ((d4 - d3) + (d5 - d6))));
    }
    let denom = 1.0 / (va + vb + vc);
    let (v, w) = (vb * denom, vc * denom);
    at([
        a[0] + ab[0] * v + ac[0] * w,
        a[1] + ab[1] * v + ac[1] * w,
        a[2] + ab[2] * v + ac[2] * w,
    ])
}

/// The sample points of `mesh` (its triangles `tris`) under `sampling`.
fn samples(mesh: &Mesh, tris: &[[V3; 3]], sampling: Sampling) -> Vec<V3> {
    match sampling {
        Sampling::Dense => {
            let mut out = Vec::with_capacity(5 * tris.len());
            for t in tris {
                for w in [
                    [1.0, 0.0, 0.0],
                    [0.5, 0.5, 0.0],
                    [0.0, 0.5, 0.5],
                    [0.5, 0.0, 0.5],
                    [1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0],
                ] {
                    out.push(std::array::from_fn(|i| {
                        w[0] * t[0][i] + w[1] * t[1][i] + w[2] * t[2][i]
                    }));
                }
            }
            out
        }
        Sampling::Capped(max) => {
            let mut out: Vec<V3> = mesh.vertices().map(|v| mesh.position(v).unwrap()).collect();
            out.extend(
                tris.iter()
                    .map(|t| [0, 1, 2].map(|k| (t[0][k] + t[1][k] + t[2][k]) / 3.0)),
            );
            let step = out.len().div_ceil(max).max(1);
            out.into_iter().step_by(step).collect()
        }
    }
}

/// The largest distance from the samples of `from` to the surface `to`.
fn one_sided(from: &Mesh, from_tris: &[[V3; 3]], to: &[[V3; 3]], sampling: Sampling) -> f64 {
    samples(from, from_tris, sampling)
        .into_iter()
        .map(|p| {
            to.iter()
                .map(|t| point_triangle(p, t))
                .fold(f64::INFINITY, f64::min)
        })
        .fold(0.0, f64::max)
}

/// The bounding-box diagonal of the mesh's vertices.
pub fn diagonal(mesh: &Mesh) -> f64 {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for v in mesh.vertices() {
        let p = mesh.position(v).unwrap();
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    dot(sub(hi, lo), sub(hi, lo)).sqrt()
}

/// The symmetric Hausdorff distance between `input` and `output`
/// (sampled both ways by `sampling`), over `input`'s bounding-box
/// diagonal.
pub fn relative_hausdorff(input: &Mesh, output: &Mesh, sampling: Sampling) -> f64 {
    let (ta, tb) = (triangles(input), triangles(output));
    let there = one_sided(input, &ta, &tb, sampling);
    let back = one_sided(output, &tb, &ta, sampling);
    there.max(back) / diagonal(input)
}
