#!/usr/bin/env bash
# Speed-ups of the `parallel` feature on this machine: every parallel path of
# the library (examples/parallel_speedup.rs) and the folder command line
# (`meshloom stats DIR`), each with RAYON_NUM_THREADS=1 and =2, same binary,
# medians of REPS runs, one table. Run from the repository root:
#
#     bash bench/parallel.sh [REPS] [GRID_N] [MESH_DIR]
#
# REPS (default 5) runs per path and thread count; GRID_N (default 1414: a
# 2M-vertex grid, made by the peers kit's gen_mesh.py when it is there, else
# in memory); MESH_DIR (default ../shared/data/meshes, else
# /work/shared/data/meshes) for the command line. The command line's one-
# and two-thread runs alternate, so a change in the machine's load hits
# both; the library's run one after the other (REPS runs of a path in a
# row, the median kept), and `read`, a serial path, is the control. The load
# (`uptime`) is printed before and after: on a shared machine the figures
# are only as good as that.
set -euo pipefail

REPS=${1:-5}
GRID_N=${2:-1414}
MESH_DIR=${3:-}
if [[ -z "$MESH_DIR" ]]; then
    for d in ../shared/data/meshes /work/shared/data/meshes; do
        [[ -d "$d" ]] && MESH_DIR=$d && break
    done
fi
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT

export CARGO_INCREMENTAL=0
cargo build --quiet --release --features parallel --example parallel_speedup
cargo build --quiet --release -p meshloom-cli
TARGET=${CARGO_TARGET_DIR:-target}
EXAMPLE=$TARGET/release/examples/parallel_speedup
CLI=$TARGET/release/meshloom

INPUT=grid:$GRID_N
for gen in ../shared/peers/src/gen_mesh.py /work/shared/peers/src/gen_mesh.py; do
    if [[ -f "$gen" ]]; then
        python3 "$gen" grid "$GRID_N" "$TMP/grid.obj" >/dev/null
        INPUT=$TMP/grid.obj
        break
    fi
done

echo "load before: $(uptime)"
# Library paths: the example prints "path median min count" per path; one
# run of it per thread count and round, REPS runs of each path inside.
RAYON_NUM_THREADS=1 "$EXAMPLE" "$INPUT" "$REPS" >"$TMP/lib.1" 2>"$TMP/lib.1.err"
RAYON_NUM_THREADS=2 "$EXAMPLE" "$INPUT" "$REPS" >"$TMP/lib.2" 2>"$TMP/lib.2.err"
grep -h "vertices" "$TMP/lib.1.err" | head -1

# The command line over a folder: wall time of whole runs, alternating.
cli_times() { # threads -> one wall time in ms
    local t0 t1
    t0=$(date +%s%N)
    RAYON_NUM_THREADS=$1 "$CLI" stats "$MESH_DIR" --json >/dev/null 2>&1 || true
    t1=$(date +%s%N)
    echo $(((t1 - t0) / 1000000))
}
if [[ -n "$MESH_DIR" ]]; then
    for _ in $(seq "$REPS"); do
        cli_times 1 >>"$TMP/cli.1"
        cli_times 2 >>"$TMP/cli.2"
    done
fi
echo "load after:  $(uptime)"

python3 - "$TMP" "$MESH_DIR" <<'EOF'
import statistics, sys, os
tmp, mesh_dir = sys.argv[1], sys.argv[2]
def lib(t):
    rows = {}
    for line in open(os.path.join(tmp, f"lib.{t}")):
        f = line.split()
        if len(f) >= 4 and f[0] != "path":
            name = " ".join(f[:-3])
            rows[name] = float(f[-3])
    return rows
one, two = lib(1), lib(2)
rows = [(k, one[k], two.get(k)) for k in one]
if mesh_dir:
    c1 = [float(x) for x in open(os.path.join(tmp, "cli.1"))]
    c2 = [float(x) for x in open(os.path.join(tmp, "cli.2"))]
    rows.append((f"cli stats {mesh_dir}", statistics.median(c1), statistics.median(c2)))
print(f"{'path':<45} {'1 thread ms':>12} {'2 threads ms':>12} {'speed-up':>9}")
for name, a, b in rows:
    s = f"{a / b:.2f}x" if b else "-"
    print(f"{name:<45} {a:>12.1f} {b if b is not None else float('nan'):>12.1f} {s:>9}")
EOF
