#!/usr/bin/env bash
# Times rastray's Z-buffer beside Mesa's llvmpipe (OpenGL ES 2 without a display) on the Stanford bunny
# under the camera and lights of ../shared/perf/bunny.toml, in one run, at the editor's preview size and
# at 1920x1080, on 1 thread and on 2 (llvmpipe: LP_NUM_THREADS=0, all in the calling thread, and 2).
# Both draw the flat-shaded mesh, lit per vertex (Gouraud) and per pixel (Phong); the harness is
# scripts/llvmpipe/zbuffer_gl.c. Needs gcc and Mesa's EGL and GLES 2 headers and libraries.
# Usage, from the project root:  scripts/vs-llvmpipe.sh [BIN]   (default target/release/rastray)
set -eu
here=$(cd "$(dirname "$0")" && pwd)
bin=${1:-target/release/rastray}
scene="$here/../../shared/perf/bunny.toml"
obj="$here/../../shared/models/stanford-bunny.obj"
gl=target/perf/llvmpipe/zbuffer_gl
mkdir -p "$(dirname "$gl")"
[ "$gl" -nt "$here/llvmpipe/zbuffer_gl.c" ] || gcc -O2 -o "$gl" "$here/llvmpipe/zbuffer_gl.c" -lEGL -lGLESv2 -lm
[ -x "$bin" ] || cargo build --release
ratio() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.2f", a / b }'; }
ms() { grep -E "^$1 " | grep -oE '[0-9]+(\.[0-9]+)? ms' | head -1 | cut -d' ' -f1; }
llvmpipe() { grep -E "^llvmpipe $1 " | grep -oE 'median [0-9.]+' | cut -d' ' -f2; }
echo "Stanford bunny (69,451 triangles), median of 7 (ms); ratio = llvmpipe time / rastray time"
echo "| size | threads | llvmpipe Gouraud | rastray Gouraud | ratio | llvmpipe Phong | rastray Phong | ratio |"
echo "|---|---|---|---|---|---|---|---|"
for size in 160x96 1920x1080; do
  for threads in 1 2; do
    lp_threads=$([ "$threads" = 1 ] && echo 0 || echo "$threads")
    l=$(LP_NUM_THREADS=$lp_threads "$gl" "$obj" "${size%x*}" "${size#*x}" 7)
    r=$(RAYON_NUM_THREADS=$threads "$bin" bench throughput "$scene" -s "$size" --reps 7)
    lg=$(echo "$l" | llvmpipe Gouraud); lph=$(echo "$l" | llvmpipe Phong)
    rg=$(echo "$r" | ms Gouraud); rph=$(echo "$r" | ms Phong)
    echo "| $size | $threads | $lg | $rg | $(ratio "$lg" "$rg") | $lph | $rph | $(ratio "$lph" "$rph") |"
  done
done
