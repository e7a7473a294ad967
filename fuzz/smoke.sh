#!/usr/bin/env bash
# Bounded AFL++ runs of every fuzz target (CI's smoke run, or a longer
# campaign): fuzz/smoke.sh [SECONDS_PER_TARGET] [TARGET...]
#
# Installs cargo-afl from crates.io when it is missing and builds AFL++ with
# it (stable Rust; no nightly). Where that cannot be done (no network, no C
# compiler), it says so and exits 0: the seeds still run as plain tests
# (`cargo test -p meshloom-fuzz`). A crash or a hang fails the run (exit 1)
# and names the input; copy it into fuzz/corpus/<target>/ as a regression
# seed once fixed.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/.." && pwd)"
seconds="${1:-60}"
shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(obj off ply stl gzip buffers repair serde ops gltf)

skip() { echo "fuzz smoke: SKIPPED: $*" >&2; exit 0; }

if ! cargo afl --version >/dev/null 2>&1; then
    echo "fuzz smoke: installing cargo-afl"
    cargo install --locked cargo-afl >/dev/null 2>&1 || skip "cargo install cargo-afl failed"
fi
if ! cargo afl config --build >/dev/null 2>&1; then
    # Already built prints an error too; only a missing afl-fuzz matters.
    :
fi
export CARGO_TARGET_DIR="$root/target/afl"
(cd "$root" && nice -n 10 cargo afl build --release -p meshloom-fuzz) || skip "cargo afl build failed"

export AFL_NO_UI=1 AFL_SKIP_CPUFREQ=1 AFL_I_DONT_CARE_ABOUT_MISSING_CRASHES=1 \
    AFL_NO_AFFINITY=1 AFL_SKIP_CRASHES=1
failed=0
for t in "${targets[@]}"; do
    out="$here/out/$t"
    rm -rf "$out"
    mkdir -p "$out"
    echo "fuzz smoke: $t for ${seconds}s"
    nice -n 10 cargo afl fuzz -V "$seconds" -t 2000 -i "$here/corpus/$t" -o "$out" \
        "$CARGO_TARGET_DIR/release/$t" >"$out/afl.log" 2>&1 || {
        tail -20 "$out/afl.log" >&2
        echo "fuzz smoke: $t: afl-fuzz failed (log: $out/afl.log)" >&2
        failed=1
        continue
    }
    stats="$out/default/fuzzer_stats"
    get() { awk -F' *: *' -v k="$1" '$1 == k { print $2 }' "$stats"; }
    echo "fuzz smoke: $t: $(get execs_done) execs in $(get run_time)s," \
        "$(get corpus_count) paths, $(get edges_found) edges," \
        "$(get saved_crashes) crashes, $(get saved_hangs) hangs"
    if [ "$(get saved_crashes)" != 0 ] || [ "$(get saved_hangs)" != 0 ]; then
        ls "$out"/default/crashes "$out"/default/hangs >&2 || true
        failed=1
    fi
done
exit "$failed"
