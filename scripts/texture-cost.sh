#!/usr/bin/env bash
# What textures cost: the Khronos Duck (../shared/models/gltf/Duck.glb) at 1920x1080, drawn with
# its texture and with `materials = "object"` (the same triangles, no texture), in each
# algorithm. Prints, per binary and algorithm, the median of N renders (the time `rastray render`
# reports, which leaves out loading) of each and their ratio, as a Markdown table. Issue 31 asks
# for a ratio of at most 1.3.
#
# Usage, from the project root:  scripts/texture-cost.sh [BIN...]   (default target/release/rastray)
#   N=7 sets the number of renders per image; the binaries take turns, render by render, so that
#   other work on the machine weighs on each alike. Compare binaries by their ratios: absolute
#   times on a shared machine drift.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bins=("$@")
[ ${#bins[@]} -gt 0 ] || bins=("$root/target/release/rastray")
runs=${N:-7}
duck=$(realpath "${DUCK:-$root/../shared/models/gltf/Duck.glb}")
work=$(mktemp -d "${TMPDIR:-/tmp}/rastray-texture-cost.XXXXXX")
trap 'rm -rf "$work"' EXIT

for look in textured object; do
  materials=file
  [ "$look" = object ] && materials=object
  cat >"$work/$look.toml" <<EOF
background = [0.1, 0.1, 0.1]
ambient = 0.2
[[light]]
position = [2.0, 3.0, 4.0]
intensity = 0.8
[camera]
position = [1.2, 1.0, 3.0]
target = [0.0, 0.0, 0.0]
fov = 40.0
[[object]]
type = "mesh"
path = "$duck"
materials = "$materials"
EOF
done

# The render time in ms that `rastray render` prints.
render_ms() {
  "$1" render --no-config "$work/$3.toml" -a "$2" -s 1920x1080 -o "$work/out.png" 2>&1 |
    sed -n 's/.* rendered in \([0-9.]*\) ms.*/\1/p'
}
median() { sort -g | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }

echo "| binary | algorithm | untextured ms | textured ms | ratio |"
echo "|---|---|---|---|---|"
for algorithm in gouraud phong ray; do
  for b in "${!bins[@]}"; do : >"$work/times-$b-textured"; : >"$work/times-$b-object"; done
  for ((i = 0; i < runs; i++)); do
    for b in "${!bins[@]}"; do
      for look in object textured; do
        render_ms "${bins[$b]}" "$algorithm" "$look" >>"$work/times-$b-$look"
      done
    done
  done
  for b in "${!bins[@]}"; do
    plain=$(median <"$work/times-$b-object")
    textured=$(median <"$work/times-$b-textured")
    ratio=$(awk -v a="$plain" -v b="$textured" 'BEGIN { printf "%.2f", b / a }')
    echo "| ${bins[$b]} | $algorithm | $plain | $textured | $ratio× |"
  done
done
