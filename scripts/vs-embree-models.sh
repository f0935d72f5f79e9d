#!/usr/bin/env bash
# Times rastray's ray tracer and BVH build beside Embree 3 on every OBJ model in ../shared/models (or the
# OBJ files given), each in its own coordinates, seen whole by the same camera under the same two lights,
# on 2 threads with shadows, in one run: the check that speed on the two perf scenes carries over to
# meshes of other shapes and sizes. Ratio = Embree time / rastray time (above 1: rastray is faster).
# Usage, from the project root:  scripts/vs-embree-models.sh [SIZE] [BIN] [MODEL.obj ...]
# Needs the Embree harness that ../shared/perf/vs-embree.sh builds into target/perf/ (run it once).
set -eu
here=$(cd "$(dirname "$0")" && pwd)
size=${1:-1920x1080}
bin=${2:-target/release/rastray}
shift $(( $# < 2 ? $# : 2 ))
models=("$@")
[ ${#models[@]} -gt 0 ] || models=("$here"/../../shared/models/*.obj)
out=target/perf/models
embree=target/perf/embree_bench
[ -x "$embree" ] || { echo "run ../shared/perf/vs-embree.sh once first: it builds $embree" >&2; exit 1; }
[ -x "$bin" ] || cargo build --release
mkdir -p "$out"
ratio() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.2f", a / b }'; }
num() { grep -oE "$1" | head -1 | grep -oE '[0-9]+(\.[0-9]+)?' | tail -1; }
echo "$size, 2 threads, shadows on, median of 5 (ms)"
echo "| model | triangles | Embree trace | rastray trace | ratio | Embree build | rastray build | ratio |"
echo "|---|---|---|---|---|---|---|---|"
for obj in "${models[@]}"; do
  name=$(basename "$obj" .obj)
  obj=$(cd "$(dirname "$obj")" && pwd)/$(basename "$obj")
  # The model's box in its own coordinates; the camera looks at its centre from the front, a little above
  # and to the right, near enough that the model fills most of a 45° view; the lights sit around it.
  read -r eye target l0 l1 < <(awk '$1 == "v" {
      for (i = 0; i < 3; i++) { x = $(i + 2); if (n == 0 || x < lo[i]) lo[i] = x; if (n == 0 || x > hi[i]) hi[i] = x }
      n++ }
    END {
      for (i = 0; i < 3; i++) { c[i] = (lo[i] + hi[i]) / 2; r2 += (hi[i] - lo[i]) ^ 2 / 4 }
      d = 0.8 * sqrt(r2) / sin(3.14159265 / 8)
      split("0.4 0.3 0.866", e, " "); split("-3 4 4", k, " "); split("4 1.5 2.5", f, " ")
      printf "%.6g,%.6g,%.6g %.6g,%.6g,%.6g ", c[0] + d * e[1], c[1] + d * e[2], c[2] + d * e[3], c[0], c[1], c[2]
      s = sqrt(r2) / 2
      printf "%.6g,%.6g,%.6g %.6g,%.6g,%.6g\n", c[0] + s * k[1], c[1] + s * k[2], c[2] + s * k[3], c[0] + s * f[1], c[1] + s * f[2], c[2] + s * f[3]
    }' "$obj")
  toml="$out/$name.toml"
  {
    echo "ambient = 0.1"
    echo "max_depth = 0"
    echo "[camera]"
    echo "position = [$eye]"
    echo "target = [$target]"
    echo "up = [0.0, 1.0, 0.0]"
    echo "fov = 45.0"
    echo "[[light]]"; echo "position = [$l0]"; echo "intensity = 0.8"
    echo "[[light]]"; echo "position = [$l1]"; echo "intensity = 0.4"
    echo "[[object]]"
    echo "type = \"mesh\""
    echo "name = \"$name\""
    echo "path = \"$obj\""
    echo "position = [$target]"
    echo "smooth = false"
    echo "material = { color = [0.9, 0.7, 0.5], diffuse = 0.7, specular = 0.3, shininess = 32.0 }"
  } > "$toml"
  e=$("$embree" obj "$obj" "size=$size" threads=2 frames=5 shadows=1 "eye=$eye" "target=$target" up=0,1,0 fov=45 \
    "light=$l0,0.8" "light=$l1,0.4")
  r=$("$bin" bench throughput "$toml" -s "$size" --reps 5)
  tris=$(echo "$r" | num '[0-9]+ triangles')
  e_t=$(echo "$e" | num 'render_8 .*\(([0-9.]+) ms/frame\)')
  e_b=$(echo "$e" | num 'build_ms +[0-9.]+')
  r_t=$(echo "$r" | num 'tracing [0-9.]+ ms')
  r_b=$(echo "$r" | num 'BVH build [0-9.]+ ms')
  printf '| %s | %s | %s | %s | %s | %s | %s | %s |\n' "$name" "$tris" "$e_t" "$r_t" "$(ratio "$e_t" "$r_t")" \
    "$e_b" "$r_b" "$(ratio "$e_b" "$r_b")"
done
