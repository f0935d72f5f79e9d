#!/usr/bin/env bash
# Checks that two rastray binaries draw byte-identical images: renders every scenes/*.toml and the
# perf scenes beside ../shared/perf with each algorithm at the editor's preview size and at
# 1920x1080, on 1 and 2 threads, with both binaries, and compares the PNGs' sha256.
# Usage, from the project root:  scripts/image-hashes.sh OLD_BIN NEW_BIN [ALGORITHMS]
#   ALGORITHMS defaults to "gouraud phong ray". Prints one line per image that differs and a
#   summary; exits 1 when any differs.
set -eu
old=$1
new=$2
algorithms=${3:-gouraud phong ray}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
scenes=(scenes/*.toml)
for perf in ../shared/perf/bunny.toml ../shared/perf/icosphere.toml; do
  [ -f "$perf" ] && scenes+=("$perf")
done
same=0
differ=0
for scene in "${scenes[@]}"; do
  for algorithm in $algorithms; do
    for size in 160x96 1920x1080; do
      for threads in 1 2; do
        hashes=()
        for bin in "$old" "$new"; do
          png="$out/image.png"
          RAYON_NUM_THREADS=$threads "$bin" render "$scene" -a "$algorithm" -s "$size" -o "$png" >/dev/null
          hashes+=("$(sha256sum "$png" | cut -d' ' -f1)")
        done
        if [ "${hashes[0]}" = "${hashes[1]}" ]; then
          same=$((same + 1))
        else
          differ=$((differ + 1))
          echo "differs: $scene $algorithm $size, $threads thread(s)"
        fi
      done
    done
  done
done
echo "$same images identical, $differ differ"
[ "$differ" -eq 0 ]
