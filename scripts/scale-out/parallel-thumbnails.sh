#!/usr/bin/env bash
# Thumbnails of many models by JOBS local jobs under GNU parallel, each one shard of the list:
# the same files, byte for byte, as one `rastray render MODELS... -o 'OUTDIR/{stem}.png'`.
#
# Usage: parallel-thumbnails.sh OUTDIR JOBS MODEL... [-- RENDER FLAGS...]
#   e.g. parallel-thumbnails.sh thumbs 8 models/*.obj models/*.glb -- -s 256x256
# RASTRAY names the binary (default: rastray on the PATH).
set -euo pipefail
if [ $# -lt 3 ]; then
  sed -n '5,7p' "$0" >&2
  exit 2
fi
rastray=${RASTRAY:-rastray}
out=$1 jobs=$2
shift 2
models=()
while [ $# -gt 0 ] && [ "$1" != "--" ]; do
  models+=("$1")
  shift
done
[ $# -gt 0 ] && shift
# Every job is given the whole list: --shard picks its slice of the sorted inputs.
parallel --halt now,fail=1 -j "$jobs" \
  "$rastray" render "${models[@]}" --shard "{}/$jobs" -o "$out/{stem}.png" "$@" \
  ::: $(seq 1 "$jobs")
