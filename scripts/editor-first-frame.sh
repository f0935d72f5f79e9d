#!/usr/bin/env bash
# Start-up to first frame of the editor on a model or scene: opens it RUNS times in a detached
# tmux session of 160x48 cells (its own tmux server), polling the screen every 20 ms until the
# status bar shows the first frame's render time. Prints each run's wall time from launching the
# editor to that screen, and what the editor logs to RASTRAY_LATENCY_LOG as its first line (from
# loading the input to the first frame drawn; builds without that line print "-").
# Usage, from the project root:
#   scripts/editor-first-frame.sh BIN MODEL [RUNS] [THREADS]
# Defaults: 5 runs, 2 threads.
set -eu
log=$(mktemp)
tmux_=(tmux -L "rastray-first-frame-$$")
trap '"${tmux_[@]}" kill-server 2>/dev/null || true; rm -f "$log"' EXIT
bin=$(realpath "$1") model=$(realpath "$2") runs=${3:-5} threads=${4:-2}

echo "editor start-up to first frame, $(basename "$model"), $threads threads, $(basename "$bin")"
echo "| run | wall (s) | logged (s) |"
echo "|---|---|---|"
for run in $(seq "$runs"); do
  : >"$log"
  start=$(date +%s.%N)
  "${tmux_[@]}" new-session -d -s first -x 160 -y 48 \
    "RASTRAY_LATENCY_LOG=$log RAYON_NUM_THREADS=$threads $bin $model"
  wall=timeout
  for _ in $(seq 3000); do
    if "${tmux_[@]}" capture-pane -p -t first 2>/dev/null | grep -q " ms │"; then
      wall=$(echo "$(date +%s.%N) - $start" | bc | xargs printf "%.3f")
      break
    fi
    sleep 0.02
  done
  sleep 0.2
  logged=$(head -n 1 "$log" | awk '{ if ($1 != "") printf "%.3f", $1 / 1000; else print "-" }')
  echo "| $run | $wall | ${logged:--} |"
  "${tmux_[@]}" send-keys -t first q
  sleep 0.5
  "${tmux_[@]}" kill-server 2>/dev/null || true
done
