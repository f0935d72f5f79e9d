#!/usr/bin/env bash
# A turntable rendered by JOBS local jobs under GNU parallel, each one shard of the frames, then
# joined into one animation: byte for byte the file of one `rastray render --turntable` run.
#
# Usage: parallel-turntable.sh SCENE FRAMES JOBS OUT.gif|OUT.png [RENDER FLAGS...]
#   e.g. parallel-turntable.sh scenes/teapot.toml 120 4 spin.gif -s 640x360 --samples 2
# RASTRAY names the binary (default: rastray on the PATH).
set -euo pipefail
if [ $# -lt 4 ]; then
  sed -n '5,7p' "$0" >&2
  exit 2
fi
rastray=${RASTRAY:-rastray}
scene=$1 frames=$2 jobs=$3 out=$4
shift 4
frames_dir=$(mktemp -d "${TMPDIR:-/tmp}/rastray-frames.XXXXXX")
trap 'rm -rf "$frames_dir"' EXIT
# {} is parallel's job argument (the shard number); {frame:04} is rastray's, left alone by
# parallel. --halt stops the other jobs when one fails.
parallel --halt now,fail=1 -j "$jobs" \
  "$rastray" render "$scene" --turntable "$frames" --shard "{}/$jobs" \
  -o "$frames_dir/{frame:04}.png" "$@" \
  ::: $(seq 1 "$jobs")
"$rastray" join "$frames_dir"/*.png -o "$out"
