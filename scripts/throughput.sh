#!/usr/bin/env bash
# Throughput of thumbnails: 256x256 Phong images of the models in ../shared/models and
# ../shared/models/gltf, repeated to N files (default 200), made three ways:
#   1. one `rastray render` process for all of them (-o 'out/{stem}.png'),
#   2. one `rastray` process per file,
#   3. F3D, one `xvfb-run f3d --output=… --resolution=256,256 FILE` per file, as its users must
#      (apt-get install -y f3d xvfb; skipped with a note when absent).
# Prints models per second for each, as a Markdown table. Wall-clock times: on a shared machine,
# say so with the numbers.
#
# Usage: scripts/throughput.sh [RASTRAY_BINARY] [N]   (default target/release/rastray, 200)
# F3D_FILES=K runs F3D on the first K files only (its rate is per model either way).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
rastray=${1:-$root/target/release/rastray}
count=${2:-200}
models_dir=${MODELS:-$root/../shared/models}
work=$(mktemp -d "${TMPDIR:-/tmp}/rastray-throughput.XXXXXX")
trap 'rm -rf "$work"' EXIT

models=()
for m in "$models_dir"/*.obj "$models_dir"/gltf/*.glb; do
  [ -f "$m" ] && models+=("$m")
done
[ ${#models[@]} -gt 0 ] || { echo "no models in $models_dir" >&2; exit 2; }
mkdir -p "$work/in"
for ((i = 0; i < count; i++)); do
  m=${models[$((i % ${#models[@]}))]}
  ln -s "$m" "$work/in/$(printf '%03d' "$i")-$(basename "$m")"
done
files=("$work"/in/*)

now() { date +%s.%N; }
rate() { awk -v n="$1" -v a="$2" -v b="$3" 'BEGIN { printf "%.2f", n / (b - a) }'; }
secs() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.2f", b - a }'; }

flags=(--no-config -a phong -s 256x256)

t0=$(now)
# Warnings (textures rastray does not draw) go to a log, not the table.
"$rastray" render "${flags[@]}" -o "$work/batch/{stem}.png" "${files[@]}" > /dev/null 2>> "$work/log"
t1=$(now)
batch_rate=$(rate "$count" "$t0" "$t1")
batch_secs=$(secs "$t0" "$t1")

mkdir -p "$work/each"
t0=$(now)
for f in "${files[@]}"; do
  "$rastray" render "${flags[@]}" -o "$work/each/$(basename "$f").png" "$f" > /dev/null 2>> "$work/log"
done
t1=$(now)
each_rate=$(rate "$count" "$t0" "$t1")
each_secs=$(secs "$t0" "$t1")

f3d_line="| F3D, one process per file (xvfb-run) | not installed | - |"
if command -v f3d > /dev/null && command -v xvfb-run > /dev/null; then
  f3d_count=${F3D_FILES:-$count}
  mkdir -p "$work/f3d"
  t0=$(now)
  for f in "${files[@]:0:$f3d_count}"; do
    xvfb-run -a f3d --output="$work/f3d/$(basename "$f").png" --resolution=256,256 "$f" > /dev/null 2>&1 || true
  done
  t1=$(now)
  f3d_rate=$(rate "$f3d_count" "$t0" "$t1")
  f3d_line="| F3D $(f3d --version 2>/dev/null | head -1 | awk '{print $NF}'), one process per file (xvfb-run) | $(secs "$t0" "$t1") s for $f3d_count | $f3d_rate |"
fi

echo "| way ($count files, 256x256 Phong) | wall time | models per second |"
echo "| --- | --- | --- |"
echo "| rastray, one batch process | $batch_secs s | $batch_rate |"
echo "| rastray, one process per file | $each_secs s | $each_rate |"
echo "$f3d_line"
echo
echo "machine: $(nproc) cores, $(uname -m); load average at the end: $(cut -d' ' -f1-3 /proc/loadavg)"
