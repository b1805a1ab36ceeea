#!/usr/bin/env bash
# What a viewer costs the nodes (docs/view.md): the demo (leader, follower, twin at 1 kHz) runs
# for SECONDS twice, once alone and once with `teleop view` attached (under its own Xvfb unless
# DISPLAY is set); each time the follower's and the twin's CPU over the middle of the run (from
# /proc) and their loops' lateness and overruns (from their reports) are printed. The view only
# reads, so the nodes should show no difference beyond the noise of a shared machine.
# Usage: bench/view_node_cpu.sh [SECONDS (default 20)] [DOMAIN (default 160)]
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-20}
domain=${2:-160}
bin=build/default/bin
out=$(mktemp -d /tmp/teleop-view-cpu-XXXXXX)

# utime + stime of a process in seconds
cpu_s() { awk -v hz="$(getconf CLK_TCK)" '{ printf "%.2f", ($14 + $15) / hz }' "/proc/$1/stat"; }

run() {
  local label=$1 viewer=$2
  "$bin/teleop" launch config/scenarios/demo.yaml --domain "$domain" --duration "$seconds" \
    --report-dir "$out/$label" > "$out/$label.txt" 2>&1 &
  local launch=$!
  sleep 3
  local view_pid=""
  if [ "$viewer" = yes ]; then
    "$bin/teleop" view --domain "$domain" --width 1280 --height 720 > "$out/$label-view.txt" 2>&1 &
    view_pid=$!
  fi
  local follower twin
  follower=$(pgrep -P "$launch" -x teleop_follower)
  twin=$(pgrep -P "$launch" -x teleop_twin)
  local f0 t0 f1 t1 window=$((seconds - 6))
  f0=$(cpu_s "$follower"); t0=$(cpu_s "$twin")
  sleep "$window"
  f1=$(cpu_s "$follower"); t1=$(cpu_s "$twin")
  local v=""
  if [ -n "$view_pid" ]; then
    v=$(cpu_s "$view_pid")
    kill -INT "$view_pid"
    wait "$view_pid" || true
  fi
  wait "$launch" || true
  for node in follower twin; do
    local c0 c1
    if [ $node = follower ]; then c0=$f0; c1=$f1; else c0=$t0; c1=$t1; fi
    printf "%-12s %-9s cpu %5.1f %% of a core  lateness p99 %6s us  overruns %s\n" "$label" "$node" \
      "$(awk -v a="$c0" -v b="$c1" -v w="$window" 'BEGIN { print 100 * (b - a) / w }')" \
      "$(awk '/^lateness_p99_ns:/ { printf "%.0f", $2 / 1000 }' "$out/$label/$node.yaml")" \
      "$(awk '/^overruns:/ { print $2 }' "$out/$label/$node.yaml")"
  done
  if [ -n "$v" ]; then echo "$label    view: $(tail -1 "$out/$label-view.txt") (cpu ${v} s in all)"; fi
}

if [ -z "${DISPLAY:-}" ]; then
  exec xvfb-run -a -s "-screen 0 1600x1200x24" "$0" "$@"
fi
run alone no
run with_view yes
echo "(reports in $out)"
