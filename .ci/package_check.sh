#!/usr/bin/env bash
# The published packages hold our own code only: no benchmark program of the
# peers kit, no test data, no CI scripts, no pictures.
set -euo pipefail
cd "$(dirname "$0")/.."
bad=0
for pkg in meshloom meshloom-cli; do
    list=$(cargo package --list --allow-dirty -p "$pkg")
    found=$(grep -E '(^|/)(data|docs|fuzz|\.ci|shared)/|bench_peers|ml_bench|\.(off|obj|ply|stl|gltf|glb|bin|gz|png|mtl)$' <<<"$list" || true)
    if [ -n "$found" ]; then
        echo "package $pkg would ship files that are not library code:" >&2
        echo "$found" >&2
        bad=1
    else
        echo "package $pkg: $(wc -l <<<"$list") files, none of them data or benchmark programs"
    fi
done
exit $bad
