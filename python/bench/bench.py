"""Benchmarks of the Python bindings, medians of repeated runs, printed as a
table. Targets (issue 16) are checked here, never in the tests.

Run from a release build, in an environment with the halfedge package (the
benchmark's own; the test suite never installs it):

    python3 -m venv .venv-bench && .venv-bench/bin/pip install maturin numpy halfedge
    cd python && VIRTUAL_ENV=../.venv-bench ../.venv-bench/bin/maturin develop --release
    ../.venv-bench/bin/python bench/bench.py [--grid /tmp/grid500.obj]

The 250k-vertex grid is `python3 ../../shared/peers/src/gen_mesh.py grid 500
/tmp/grid500.obj`; without it a grid of the same size is made with numpy.

Workloads:
1. `Mesh.from_arrays` on the 250k-vertex triangle grid, beside the Rust
   builder (`Mesh::from_buffers`) timed inside the same process on the same
   polygons. Target: within 1.5x.
2. The halfedge package's workload side by side: build a 10k-triangle grid
   from a vertex list and face-index list, then remove 1,000 edges picked at
   random from the edge list (an edge an operator refuses is skipped and
   another one picked, in both libraries). Target: meshloom >= 100x faster.
3. A float vertex attribute of all 250k vertices read into numpy, beside
   `numpy.ndarray.copy()` of an array of the same size. Target: <= 2x.
   Also (no target): the same column written from numpy
   (`set_attr_array`), and a vec3 column read as (n, 3).
4. The price of all-or-nothing Python rules: 1,000 `split_edge` calls on
   the 10k-triangle mesh with a float vertex column (stock rule, no
   transaction), and with a vertex column of a Python rule (each edit in a
   journal transaction, plus the Python calls); for scale, a whole-mesh
   clone (`Mesh.copy()`, what an edit cost before the transaction) of the
   10k and the 250k mesh.
"""

from __future__ import annotations

import argparse
import os
import random
import statistics
import sys
import time

import numpy as np

import meshloom


def median_seconds(fn, repeats):
    times = []
    for _ in range(repeats):
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return statistics.median(times)


def tri_grid(nx, ny):
    """nx * ny quads cut into 2 triangles each: (nx+1)(ny+1) vertices."""
    xs, ys = np.meshgrid(np.arange(nx + 1, dtype=float), np.arange(ny + 1, dtype=float))
    positions = np.column_stack([xs.ravel(), ys.ravel(), np.zeros(xs.size)])
    j, i = np.meshgrid(np.arange(ny), np.arange(nx), indexing="ij")
    a = (j * (nx + 1) + i).ravel()
    b, c, d = a + 1, a + nx + 2, a + nx + 1
    faces = np.concatenate([np.column_stack([a, b, c]), np.column_stack([a, c, d])])
    return positions, faces.astype(np.int64)


def bench_from_arrays(grid_path, repeats):
    if grid_path and os.path.exists(grid_path):
        positions, faces = meshloom.read(grid_path).to_arrays()
        source = grid_path
    else:
        positions, faces = tri_grid(499, 499)
        source = "numpy grid 499 x 499 quads"
    mesh = meshloom.Mesh.from_arrays(positions, faces)
    py = median_seconds(lambda: meshloom.Mesh.from_arrays(positions, faces), repeats)
    rust = statistics.median(mesh._rust_build_seconds(repeats))
    return source, mesh.vertex_count, py, rust


def halfedge_workload(vl, fi, removals, seed):
    import halfedge

    class Coordinate(halfedge.Vector3Attrib):
        pass

    t = time.perf_counter()
    mesh = halfedge.HalfEdges.from_vlfi([halfedge.Vert(Coordinate(tuple(p))) for p in vl], fi)
    build = time.perf_counter() - t
    rng = random.Random(seed)
    t = time.perf_counter()
    done = tried = 0
    # Removing an edge makes no new edges, so picking among the surviving
    # edges of the first list is picking from the current edge list.
    edges = list(mesh.edges)
    while done < removals:
        edge = rng.choice(edges)
        if edge not in mesh.edges:
            continue
        tried += 1
        try:
            mesh.remove_edge(edge)
        except ValueError:
            continue
        done += 1
    remove = time.perf_counter() - t
    return build, remove, tried


def meshloom_workload(vl, fi, removals, seed):
    t = time.perf_counter()
    mesh = meshloom.Mesh.from_arrays(vl, fi)
    build = time.perf_counter() - t
    rng = random.Random(seed)
    t = time.perf_counter()
    done = tried = 0
    edges = mesh.edges
    while done < removals:
        # As in the halfedge run: among the surviving edges of the first list.
        edge = rng.choice(edges)
        if not edge.is_alive:
            continue
        tried += 1
        try:
            mesh.remove_edge(edge)
        except meshloom.RefusedError:
            continue
        done += 1
    remove = time.perf_counter() - t
    mesh.validate()
    return build, remove, tried


def bench_attr_read(positions, faces, repeats):
    mesh = meshloom.Mesh.from_arrays(positions, faces)
    mesh.add_vertex_attr("t", float)
    values = np.random.default_rng(0).random(mesh.vertex_count)
    mesh.set_attr_array("t", values)
    read = median_seconds(lambda: mesh.attr_array("t"), repeats)
    copy = median_seconds(lambda: values.copy(), repeats)
    write = median_seconds(lambda: mesh.set_attr_array("t", values), repeats)
    mesh.add_vertex_attr("v", "vec3")
    vectors = np.random.default_rng(1).random((mesh.vertex_count, 3))
    mesh.set_attr_array("v", vectors)
    read3 = median_seconds(lambda: mesh.attr_array("v"), repeats)
    copy3 = median_seconds(lambda: vectors.copy(), repeats)
    return mesh.vertex_count, read, copy, write, read3, copy3


class Mean:
    def merge(self, values, weights):
        present = [(v, w) for v, w in zip(values, weights) if v is not None]
        total = sum(w for _, w in present) or 1.0
        return sum(v * w for v, w in present) / total

    def split(self, value, share):
        return value


def bench_rule_cost(positions, faces, big, repeats):
    out = {}
    for label, rule in (("stock float column", None), ("Python-rule column", Mean())):
        times = []
        for _ in range(repeats):
            mesh = meshloom.Mesh.from_arrays(positions, faces)
            if rule is None:
                mesh.add_vertex_attr("t", float)
                mesh.set_attr_array("t", np.arange(mesh.vertex_count, dtype=float))
            else:
                mesh.add_vertex_attr("t", rule=rule)
                for i, v in enumerate(mesh.vertices):
                    mesh.set_attr("t", v, float(i))
            edges = mesh.edges[:1000]
            t = time.perf_counter()
            for e in edges:
                mesh.split_edge(e)
            times.append(time.perf_counter() - t)
        out[label] = statistics.median(times)
    small = meshloom.Mesh.from_arrays(positions, faces)
    out["copy 10k"] = median_seconds(small.copy, repeats)
    out["copy 250k"] = median_seconds(big.copy, repeats)
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--grid", default="/tmp/grid500.obj")
    ap.add_argument("--repeats", type=int, default=9)
    ap.add_argument("--halfedge-runs", type=int, default=3)
    args = ap.parse_args()

    print(f"python {sys.version.split()[0]}, numpy {np.__version__}, meshloom {meshloom.__version__}")
    print(f"load average at start: {os.getloadavg()}")

    source, n, py, rust = bench_from_arrays(args.grid, args.repeats)
    print(f"\n1. from_arrays, {n} vertices ({source}), median of {args.repeats}")
    print(f"   Mesh.from_arrays {py * 1e3:8.1f} ms   Rust builder {rust * 1e3:8.1f} ms   ratio {py / rust:.2f} (target <= 1.5)")

    positions, faces = tri_grid(100, 50)  # 10,000 triangles
    vl = positions.tolist()
    fi = [tuple(f) for f in faces.tolist()]
    hb, hr, mb, mr = [], [], [], []
    tries = []
    for run in range(args.halfedge_runs):
        try:
            b, r, t1 = halfedge_workload(vl, fi, 1000, seed=run)
        except ImportError:
            print("\n2. halfedge is not installed: pip install halfedge (in the benchmark's venv)")
            break
        hb.append(b)
        hr.append(r)
        b2, r2, t2 = meshloom_workload(vl, fi, 1000, seed=run)
        mb.append(b2)
        mr.append(r2)
        tries.append((t1, t2))
    if hb:
        h_total = statistics.median(b + r for b, r in zip(hb, hr))
        m_total = statistics.median(b + r for b, r in zip(mb, mr))
        print(f"\n2. halfedge workload: 10,000 triangles from lists, remove 1,000 random edges; median of {len(hb)}")
        print(f"   halfedge {__import__('halfedge').__name__}: build {statistics.median(hb) * 1e3:8.1f} ms  remove {statistics.median(hr) * 1e3:8.1f} ms")
        print(f"   meshloom:          build {statistics.median(mb) * 1e3:8.1f} ms  remove {statistics.median(mr) * 1e3:8.1f} ms")
        print(f"   edges picked (halfedge, meshloom) per run: {tries}")
        print(f"   speed-up {h_total / m_total:.0f}x (build {statistics.median(hb) / statistics.median(mb):.0f}x, remove {statistics.median(hr) / statistics.median(mr):.0f}x; target >= 100x)")

    if args.grid and os.path.exists(args.grid):
        positions, faces = meshloom.read(args.grid).to_arrays()
    else:
        positions, faces = tri_grid(499, 499)
    n, read, copy, write, read3, copy3 = bench_attr_read(positions, faces, args.repeats * 5)
    print(f"\n3. float vertex attribute of {n} vertices into numpy, median of {args.repeats * 5}")
    print(f"   attr_array {read * 1e6:8.1f} us   ndarray.copy {copy * 1e6:8.1f} us   ratio {read / copy:.2f} (target <= 2)")
    print(f"   set_attr_array {write * 1e6:8.1f} us   ratio to ndarray.copy {write / copy:.2f}")
    print(f"   vec3 attr_array {read3 * 1e6:8.1f} us   ndarray.copy (n, 3) {copy3 * 1e6:8.1f} us   ratio {read3 / copy3:.2f}")

    big = meshloom.Mesh.from_arrays(positions, faces)
    small_p, small_f = tri_grid(100, 50)
    cost = bench_rule_cost(small_p, small_f, big, args.repeats)
    print(f"\n4. all-or-nothing Python rules: 1,000 split_edge on 10,000 triangles, median of {args.repeats}")
    for label in ("stock float column", "Python-rule column"):
        print(f"   {label:20s} {cost[label] * 1e3:8.1f} ms  ({cost[label] * 1e6 / 1000:.1f} us per edit)")
    print(f"   for scale, a whole-mesh clone (Mesh.copy) of the 10k mesh {cost['copy 10k'] * 1e6:8.1f} us, of the 250k mesh {cost['copy 250k'] * 1e3:8.1f} ms")
    print(f"\nload average at end: {os.getloadavg()}")


if __name__ == "__main__":
    main()
