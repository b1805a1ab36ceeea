#!/usr/bin/env bash
# The recorder and the replay at the full demo load (issues 19 and 30, docs/recording.md): the
# demo scenario (leader, follower, twin at 1 kHz, every topic) runs for SECONDS while two `teleop
# record`s take every topic side by side, one into an MCAP file (zstd, the default) and one into a
# sqlite3 bag; then the MCAP recording is replayed onto an empty domain. Prints each recorder's
# samples, bytes, drops, upstream gaps and CPU, and the replay's timing errors. A benchmark, not a
# test: the numbers depend on the machine and its load.
# Usage: bench/record_replay_bench.sh [SECONDS (default 20)] [DOMAIN (default 150)]
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-20}
domain=${2:-150}
bin=build/default/bin
out=$(mktemp -d /tmp/teleop-record-bench-XXXXXX)
record() {  # NAME, then record's own options
  local name=$1
  shift
  "$bin/teleop" record --domain "$domain" --duration $((seconds + 4)) "$@" > "$out/$name.txt" 2> "$out/$name.log"
}
record mcap -o "$out/run.mcap" &
mcap_recorder=$!
record sqlite3 -o "$out/bag" --storage sqlite3 &
sqlite_recorder=$!
sleep 1
"$bin/teleop" launch config/scenarios/demo.yaml --domain "$domain" --duration "$seconds" --report-dir "$out/reports" \
  > "$out/launch.txt" 2>&1
wait "$mcap_recorder" "$sqlite_recorder"
for name in mcap sqlite3; do
  echo "== record ($name): the demo for ${seconds} s, every topic"
  cat "$out/$name.txt"
done
for file in "$out/run.mcap" "$out/bag/bag_0.db3"; do
  bytes=$(stat -c %s "$file")
  echo "$file: $bytes bytes, $(awk -v b="$bytes" -v s="$seconds" 'BEGIN { printf "%.0f", b / s }') bytes/s of demo"
done
"$bin/teleop" bag info "$out/run.mcap"
echo "== replay: the MCAP recording, everything, onto an empty domain"
"$bin/teleop" replay "$out/run.mcap" --domain $((domain + 1)) --wait-for-readers 0 2> /dev/null
echo "(recordings and reports in $out)"
