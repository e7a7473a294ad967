#!/usr/bin/env bash
# Build the seed corpora in fuzz/corpus/<target>/ from the shared test
# meshes (small files only, text files cut to their first 200 lines, so the
# committed corpus stays small) and from the synthetic seeds in code.
# Usage: fuzz/seeds.sh   (from anywhere; needs ../shared/data/meshes)
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
data="$here/../../shared/data/meshes"
corpus="$here/corpus"
[ -d "$data" ] || { echo "seeds: $data is missing" >&2; exit 1; }
mkdir -p "$corpus"/{obj,off,ply,stl,gzip}
max=6000   # bytes per seed
for f in "$data"/*/*.{obj,off,ply,stl}; do
    [ -f "$f" ] || continue
    ext="${f##*.}"
    name="$(basename "$(dirname "$f")")_$(basename "$f")"
    if [ "$(stat -c %s "$f")" -le "$max" ]; then
        cp "$f" "$corpus/$ext/$name"
    elif [ "$ext" != stl ] && head -c 4000 "$f" | grep -q $'\n'; then
        # Text (or a binary PLY's header and first bytes): a prefix.
        head -c "$max" "$f" > "$corpus/$ext/$name"
    fi
done
# gzip: a few small files, gzipped, with the format's pick byte first.
pick() { case "$1" in obj) printf '\x00';; off) printf '\x01';; ply) printf '\x02';; stl) printf '\x03';; esac; }
for f in "$data"/closed/cgal_tetrahedron.off "$data"/polygons/cgal_cube_quad.off \
         "$data"/polygons/openmesh_cube-minimal.ply "$data"/stl/compas_cube_binary.stl \
         "$data"/polygons/compas_faces.obj; do
    ext="${f##*.}"
    { pick "$ext"; gzip -9 -n -c "$f"; } > "$corpus/gzip/$(basename "$f").gz"
done
# The PLY of issue 10's defect 1 and a Blender-style header.
printf 'ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\nproperty float z\nelement vertex 1\nend_header\n\n' > "$corpus/ply/issue10_dup_vertex.ply"
printf "ply\nformat ascii 1.0\nCreated by Blender 2.79 - www.blender.org, source file: ''\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar uint vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n" > "$corpus/ply/issue10_blender.ply"
# glTF: the shared samples (a .gltf whose buffer is in another file still
# exercises the JSON) and the repros of the glTF reader's panics.
mkdir -p "$corpus/gltf"
for f in "$data"/gltf/BoxTextured.glb "$data"/gltf/BoxTextured/BoxTextured.gltf \
         "$data"/gltf/BoxTexcoords/boxTexcoords.gltf "$data"/gltf/invalid/BoxWithInfinites.glb \
         "$data"/gltf/invalid/badNumber.gltf "$data"/gltf/invalid/IndexOutOfRange/IndexOutOfRange.gltf \
         "$here"/../../shared/data/repros/gltf_*; do
    cp "$f" "$corpus/gltf/$(basename "$f")"
done
# Synthetic seeds (buffers, repair, serde, ops, meshloom's own glTF).
cargo run --quiet --manifest-path "$here/Cargo.toml" --bin seeds -- "$corpus"
du -sh "$corpus"
