"""Process a folder of meshes on several processes.

    python examples/process_folder.py IN_DIR OUT_DIR [--workers N]

Each worker reads one file (with every repair policy), closes its holes with
triangles and triangulates it, and sends the mesh back to the parent:
meshes pickle through meshloom's validated serde form, so they cross
process boundaries like any Python value. The parent writes each result as
OBJ and prints one line per file. Dask and Ray move meshes the same way
(`client.map(work, paths)` / `ray.remote(work)`).
"""

from __future__ import annotations

import argparse
import os
import sys
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import meshloom

SUFFIXES = (".obj", ".off", ".ply", ".stl", ".gz")


def work(path: str):
    """Read, close holes, triangulate; return the mesh and what happened."""
    mesh, report = meshloom.read_with(path, repair="all")
    holes = mesh.hole_count
    for hole in mesh.holes:
        try:
            mesh.fill_hole_triangulated(hole)
        except meshloom.RefusedError:
            pass  # a hole the operator refuses stays open
    mesh.triangulate_all()
    mesh.validate()
    return path, mesh, holes, sum(v for v in report.values() if isinstance(v, int))


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("input", type=Path)
    ap.add_argument("output", type=Path)
    ap.add_argument("--workers", type=int, default=os.cpu_count() or 1)
    args = ap.parse_args(argv)
    paths = sorted(str(p) for p in args.input.iterdir() if p.name.lower().endswith(SUFFIXES))
    if not paths:
        print(f"no mesh files in {args.input}", file=sys.stderr)
        return 1
    args.output.mkdir(parents=True, exist_ok=True)
    failed = 0
    with ProcessPoolExecutor(max_workers=args.workers) as pool:
        futures = [pool.submit(work, p) for p in paths]
        for future in futures:
            try:
                path, mesh, holes, repairs = future.result()
            except meshloom.MeshloomError as e:
                print(f"failed: {e}", file=sys.stderr)
                failed += 1
                continue
            out = args.output / (Path(path).name.split(".")[0] + ".obj")
            meshloom.write(mesh, out)
            print(f"{path}: {mesh.face_count} triangles, {holes} holes closed, {repairs} repairs -> {out}")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
