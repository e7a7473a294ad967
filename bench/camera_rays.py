#!/usr/bin/env python3
"""Coherent (camera) rays for the spatial-query comparison (issue 27).

    python3 bench/camera_rays.py [INPUTS]          # writes INPUTS/rays_camera_1m.obj
    PY bench/camera_rays.py --time [--rounds 3] [INPUTS]

INPUTS defaults to target/peers/inputs (the pypeers kit's files, where the
torus_100k.off and torus_2m.off this is aimed at live). The file has the
format of the kit's rays_1m.obj: one "v" (origin) and one "vn" (unit
direction) line per ray. The rays are a 1000 x 1000 pinhole camera at
(0, -3, 2.2) looking at the origin (z up, 50 degree vertical field of
view), one ray through each pixel's centre: the bumpy torus fills most of
the picture.

--time (with PY a Python that has numpy and embreex, such as the kit's
target/peers/pyvenv/bin/python) also times Embree on them, as the kit's
pypeers.py times its random rays: pinned to one CPU, process CPU time,
rounds in one process from a fresh scene, median/min/max, in the kit's
tab-separated line format, workloads ray_cast_camera_100k and
ray_cast_camera_2m with their .build. meshloom's side is
examples/query_peers.rs, parry3d's bench/parry.
"""
import os
import sys
import time

import numpy as np

EYE = np.array([0.0, -3.0, 2.2])
SIZE = 1000
FOV_DEG = 50.0


def camera_rays():
    """Origins and unit directions, row by row from the top left pixel."""
    forward = -EYE / np.linalg.norm(EYE)
    right = np.cross(forward, [0.0, 0.0, 1.0])
    right /= np.linalg.norm(right)
    up = np.cross(right, forward)
    half = np.tan(np.radians(FOV_DEG) / 2)
    s = (np.arange(SIZE) + 0.5) / SIZE * 2 - 1
    x, y = np.meshgrid(s * half, -s * half)
    d = forward + x[..., None] * right + y[..., None] * up
    d = d.reshape(-1, 3)
    d /= np.linalg.norm(d, axis=1)[:, None]
    return np.broadcast_to(EYE, d.shape), d


def write(path):
    o, d = camera_rays()
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        f.write("# %d camera rays: v = origin, vn = unit direction; eye %s, %d x %d, "
                "vertical fov %g deg, looking at the origin, z up\n"
                % (len(d), EYE.tolist(), SIZE, SIZE, FOV_DEG))
        np.savetxt(f, o, fmt="v %.17g %.17g %.17g")
        np.savetxt(f, d, fmt="vn %.17g %.17g %.17g")
    os.replace(tmp, path)


def read_off(path):
    with open(path) as f:
        lines = [l for l in f if l.strip() and not l.startswith("#")]
    nv, nf = map(int, lines[1].split()[:2])
    V = np.loadtxt(lines[2:2 + nv], dtype=np.float64, ndmin=2)
    F = np.loadtxt(lines[2 + nv:2 + nv + nf], dtype=np.int64, ndmin=2)[:, 1:4]
    return V, F


def time_embree(inputs, rounds):
    os.sched_setaffinity(0, {min(os.sched_getaffinity(0))})
    os.environ["OMP_NUM_THREADS"] = "1"
    from embreex import mesh_construction, rtcore_scene
    o, d = camera_rays()
    O32, D32 = np.ascontiguousarray(o, np.float32), np.ascontiguousarray(d, np.float32)
    print("# embreex camera rays: rounds %d, clock process CPU, one CPU; load %.2f"
          % (rounds, os.getloadavg()[0]))
    for tag in ("100k", "2m"):
        V, F = read_off(os.path.join(inputs, "torus_%s.off" % tag))
        V32, F32 = V.astype(np.float32), F.astype(np.int32)
        build, cast, hits = [], [], 0
        for _ in range(rounds):
            c0, w0 = time.process_time(), time.perf_counter()
            scene = rtcore_scene.EmbreeScene()
            mesh_construction.TriangleMesh(scene, V32, F32)
            scene.run(O32[:1], D32[:1])  # commits the scene (BVH build)
            c1, w1 = time.process_time(), time.perf_counter()
            ids = scene.run(O32, D32)
            c2, w2 = time.process_time(), time.perf_counter()
            build.append((c1 - c0, w1 - w0))
            cast.append((c2 - c1, w2 - w1))
            hits = int((ids >= 0).sum())
        name = "ray_cast_camera_" + tag
        b, bw = sorted(x for x, _ in build), sorted(w for _, w in build)
        print("%s.build\t%.6f\t%.6f\t%.6f\t%d F; wall %.3f; threads 1; EmbreeScene + TriangleMesh + commit"
              % (name, b[len(b) // 2], b[0], b[-1], len(F), bw[len(bw) // 2]))
        c, cw = sorted(x for x, _ in cast), sorted(w for _, w in cast)
        med = c[len(c) // 2]
        print("%s\t%.6f\t%.6f\t%.6f\t%d hits; wall %.3f; threads 1; %.3g rays/s; %d rays, embreex rtcIntersect1 per ray"
              % (name, med, c[0], c[-1], hits, cw[len(cw) // 2], len(O32) / med, len(O32)))


def main(argv):
    args = [a for a in argv if not a.startswith("--")]
    rounds = 3
    if "--rounds" in argv:
        rounds = int(argv[argv.index("--rounds") + 1])
        args.remove(str(rounds))
    inputs = args[0] if args else "target/peers/inputs"
    path = os.path.join(inputs, "rays_camera_1m.obj")
    if not os.path.exists(path):
        write(path)
    if "--time" in argv:
        time_embree(inputs, rounds)


if __name__ == "__main__":
    main(sys.argv[1:])
