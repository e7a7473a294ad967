//! Attributes: uniform Laplacian smoothing of positions through the
//! attribute API, and the cost of reading an attribute by key against
//! indexing a plain `Vec`.

use std::hint::black_box;

use meshloom::shapes::{self, GridFaces};
use meshloom::{Mesh, VertexKey};

use crate::harness::{Peer, Report};

/// The benchmark grid: 499 × 499 cells in triangles, 250,000 vertices.
pub(crate) fn grid() -> Mesh {
    shapes::grid(499, 499, GridFaces::Triangles)
}

/// `iterations` rounds of uniform Laplacian smoothing: every vertex moves to
/// the mean of its neighbours, reading and writing positions through the
/// position attribute's views.
pub(crate) fn smooth(
    mesh: &mut Mesh,
    vertices: &[VertexKey],
    iterations: usize,
) -> meshloom::Result<()> {
    let pos = mesh.position_attr().ok_or(meshloom::Error::NoPositions)?;
    let mut next = vec![[0.0f64; 3]; vertices.len()];
    for _ in 0..iterations {
        let view = mesh.attr_view(&pos)?;
        for (out, &v) in next.iter_mut().zip(vertices) {
            let mut sum = [0.0; 3];
            let mut n = 0.0;
            for u in mesh.vertex(v)?.neighbors() {
                if let Some(p) = view.get(u) {
                    sum[0] += p[0];
                    sum[1] += p[1];
                    sum[2] += p[2];
                    n += 1.0;
                }
            }
            *out = if n > 0.0 { sum.map(|c| c / n) } else { sum };
        }
        let mut view = mesh.attr_view_mut(&pos)?;
        for (p, &v) in next.iter().zip(vertices) {
            if let Some(slot) = view.get_mut(v) {
                *slot = *p;
            }
        }
    }
    Ok(())
}

/// The same smoothing navigating checked views: each vertex's key is
/// checked once, its ring is walked with half-edge views, and positions are
/// read with [`AttrView::at`](meshloom::attr::AttrView::at) (no generation
/// check).
pub(crate) fn smooth_views(
    mesh: &mut Mesh,
    vertices: &[VertexKey],
    iterations: usize,
) -> meshloom::Result<()> {
    let pos = mesh.position_attr().ok_or(meshloom::Error::NoPositions)?;
    let mut next = vec![[0.0f64; 3]; vertices.len()];
    for _ in 0..iterations {
        let view = mesh.attr_view(&pos)?;
        for (out, &v) in next.iter_mut().zip(vertices) {
            let start = mesh.vertex(v)?.halfedge();
            let mut h = start;
            let mut sum = [0.0; 3];
            let mut n = 0.0;
            loop {
                if let Some(p) = view.at(h.dest()) {
                    sum[0] += p[0];
                    sum[1] += p[1];
                    sum[2] += p[2];
                    n += 1.0;
                }
                h = h.rotate_cw();
                if h == start {
                    break;
                }
            }
            *out = if n > 0.0 { sum.map(|c| c / n) } else { sum };
        }
        let mut view = mesh.attr_view_mut(&pos)?;
        for (p, &v) in next.iter().zip(vertices) {
            if let Some(slot) = view.get_mut(v) {
                *slot = *p;
            }
        }
    }
    Ok(())
}

/// The same smoothing on the raw position slice and raw neighbour slots,
/// without keys or the attribute API: what the API's checks cost.
pub(crate) fn smooth_raw(mesh: &mut Mesh, vertices: &[VertexKey], iterations: usize) {
    let rings: Vec<Vec<usize>> = vertices
        .iter()
        .map(|&v| {
            mesh.vertex(v)
                .map(|x| x.neighbors().map(|u| u.index()).collect())
                .unwrap_or_default()
        })
        .collect();
    let mut next = vec![[0.0f64; 3]; vertices.len()];
    for _ in 0..iterations {
        let p = mesh.position_slots().expect("positions");
        for (out, ring) in next.iter_mut().zip(&rings) {
            let mut sum = [0.0; 3];
            for &u in ring {
                sum[0] += p[u][0];
                sum[1] += p[u][1];
                sum[2] += p[u][2];
            }
            let n = ring.len().max(1) as f64;
            *out = sum.map(|c| c / n);
        }
        let p = mesh.position_slots_mut().expect("positions");
        for (q, &v) in next.iter().zip(vertices) {
            p[v.index()] = *q;
        }
    }
}

/// Run the attribute rows.
pub fn run(r: &mut Report) {
    let mesh = grid();
    let vertices: Vec<VertexKey> = mesh.vertices().collect();
    r.time(
        "attr: 10x uniform Laplacian, 250k-vertex grid",
        Some(Peer {
            name: "pmp-library",
            seconds: 0.049,
            ratio: 1.0,
        }),
        || mesh.clone(),
        |mut m| {
            smooth(&mut m, &vertices, 10).expect("the grid has positions");
            m
        },
    );

    r.time(
        "attr: same, ring walked with views and view.at",
        Some(Peer {
            name: "pmp-library",
            seconds: 0.049,
            ratio: 1.0,
        }),
        || mesh.clone(),
        |mut m| {
            smooth_views(&mut m, &vertices, 10).expect("the grid has positions");
            m
        },
    );
    r.time(
        "attr: same on raw slices, rings precomputed (ref.)",
        None,
        || mesh.clone(),
        |mut m| {
            smooth_raw(&mut m, &vertices, 10);
            m
        },
    );

    // Reading every vertex's position 20 times into four independent sums
    // (so that the loads, not one addition chain, set the pace), with the
    // keys in slot order, then shuffled by a fixed pseudo-random
    // permutation (latency rather than bandwidth).
    let plain: Vec<[f64; 3]> = mesh.position_slots().expect("positions").to_vec();
    let pos = mesh.position_attr().expect("positions");
    let view = mesh.attr_view(&pos).expect("a live handle");
    let mut shuffled = vertices.clone();
    let mut x: u64 = 0x9E37_79B9_7F4A_7C15;
    for i in (1..shuffled.len()).rev() {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        shuffled.swap(i, (x % (i as u64 + 1)) as usize);
    }
    let orders = [
        (
            &vertices,
            ", plain Vec[index]",
            ", view.get(key)",
            "slot order",
        ),
        (&shuffled, " shuffled, Vec", " shuffled, view", "shuffled"),
    ];
    for (keys, vec_row, view_row, order) in orders {
        let vec_time = r.time(
            &format!("attr: read 250k positions x20{vec_row}"),
            None,
            || (),
            |()| sum_reads(keys, |acc, v| *acc += plain[v.index()][0]),
        );
        let attr_time = r.time(
            &format!("attr: read 250k positions x20{view_row}"),
            None,
            || (),
            |()| {
                sum_reads(keys, |acc, v| {
                    if let Some(p) = view.get(v) {
                        *acc += p[0];
                    }
                })
            },
        );
        r.figure(
            &format!("attr: read by key / plain Vec, {order}"),
            100.0 * attr_time / vec_time,
            "%",
            Some((110.0, "target")),
        );
    }
}

/// `ROUNDS` passes over `keys`, four keys at a time into four independent
/// sums; `read` adds one key's value to its sum.
#[inline(always)]
fn sum_reads(keys: &[VertexKey], read: impl Fn(&mut f64, VertexKey)) -> [f64; 4] {
    const ROUNDS: usize = 20;
    let mut s = [0.0; 4];
    for _ in 0..ROUNDS {
        for quad in black_box(keys).chunks_exact(4) {
            for (acc, &v) in s.iter_mut().zip(quad) {
                read(acc, v);
            }
        }
    }
    s
}
