#!/bin/sh
# Runs the fuzz targets kept in tests/ for a long session: 1,000,000 cases in all by default.
# Usage: scripts/fuzz.sh [TOTAL_CASES]
# The cases are shared out by cost: an editor session is up to sixty actions, a scene or model
# file (OBJ, MTL, STL, PLY, glTF) one parse. CI runs the same targets with proptest's default of 256 cases each.
set -eu
total=${1:-1000000}
# Build once, then run the test binaries themselves: the sources may change meanwhile.
binaries=$(cargo test --release --no-run --message-format=json \
        --test fuzz_scene --test fuzz_obj --test fuzz_mtl --test fuzz_stl --test fuzz_ply --test fuzz_gltf \
        --test fuzz_gltf_structure --test fuzz_editor |
    grep -o '"executable":"[^"]*"' | sed 's/"executable":"\(.*\)"/\1/')
started=$(date +%s)
for target in fuzz_scene:26 fuzz_obj:16 fuzz_mtl:6 fuzz_stl:12 fuzz_ply:12 fuzz_gltf:12 fuzz_gltf_structure:8 \
    fuzz_editor:8; do
    name=${target%%:*}
    cases=$((total * ${target#*:} / 100))
    binary=$(printf '%s\n' "$binaries" | grep "/$name-")
    echo "== $name: $cases cases"
    t0=$(date +%s)
    PROPTEST_CASES=$cases "$binary" --nocapture
    echo "== $name: $cases cases in $(($(date +%s) - t0)) s"
done
echo "== all: $total cases in $(($(date +%s) - started)) s"
