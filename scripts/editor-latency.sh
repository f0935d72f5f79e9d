#!/usr/bin/env bash
# Key-to-drawn-frame latency of the editor on a real mesh: opens SCENE in a detached tmux session
# of COLSxROWS cells (its own tmux server), and for each algorithm (keys 1, 2, 3) orbits the view
# PRESSES times with `]`, one press at a time, each after the last frame was drawn. The editor logs
# each press's latency to RASTRAY_LATENCY_LOG (key received -> frame drawn, render, draw; ms;
# its first line is the start-up);
# this prints the median and 95th percentile per algorithm.
# Usage, from the project root:
#   scripts/editor-latency.sh [BIN] [SCENE] [PRESSES] [THREADS] [COLSxROWS]
# Defaults: target/release/rastray, ../shared/perf/bunny.toml, 60, 2, 200x56 (a preview of
# about 160x96 pixels beside the scene panes).
set -eu
bin=$(realpath "${1:-target/release/rastray}")
scene=$(realpath "${2:-../shared/perf/bunny.toml}")
presses=${3:-60}
threads=${4:-2}
size=${5:-200x56}
socket="rastray-latency-$$"
log=$(mktemp)
tmux_() { tmux -L "$socket" "$@"; }
cleanup() { tmux_ kill-server 2>/dev/null || true; rm -f "$log"; }
trap cleanup EXIT

# Waits until the log holds at least $1 lines (at most 30 s).
wait_lines() {
  for _ in $(seq 600); do
    [ "$(wc -l <"$log")" -ge "$1" ] && return 0
    sleep 0.05
  done
  echo "no frame drawn after key press $1" >&2
  return 1
}

tmux_ new-session -d -s latency -x "${size%x*}" -y "${size#*x}" \
  "RASTRAY_LATENCY_LOG=$log RAYON_NUM_THREADS=$threads $bin $scene"
# The editor is up once its first frame is on the screen.
for _ in $(seq 600); do
  tmux_ capture-pane -p -t latency | grep -q " ms " && break
  sleep 0.05
done
# Its first log line is the start-up, not a key.
wait_lines 1
echo "editor latency, key -> drawn frame (ms), $presses presses of ] per algorithm, $threads threads, terminal $size, $(basename "$scene")"
echo "| algorithm | median | p95 | render median | draw median |"
echo "|---|---|---|---|---|"
for algorithm in 1:Gouraud 2:Phong 3:ray; do
  key=${algorithm%%:*}
  name=${algorithm#*:}
  count=$(wc -l <"$log")
  tmux_ send-keys -t latency "$key"
  wait_lines $((count + 1))
  # Let the ray tracer's BVH build and any refinement finish before timing.
  sleep 1
  first=$(($(wc -l <"$log") + 1))
  for i in $(seq "$presses"); do
    tmux_ send-keys -t latency "]"
    wait_lines $((first + i - 1))
    sleep 0.05
  done
  tail -n "+$first" "$log" | head -n "$presses" | python3 -c '
import statistics, sys
rows = [list(map(float, line.split())) for line in sys.stdin if line.strip()]
total = sorted(r[0] for r in rows)
p95 = total[min(len(total) - 1, int(round(0.95 * (len(total) - 1))))]
print("| %s | %.2f | %.2f | %.2f | %.2f |" % (sys.argv[1], statistics.median(total), p95,
      statistics.median(r[1] for r in rows), statistics.median(r[2] for r in rows)))
' "$name"
done
tmux_ send-keys -t latency q
