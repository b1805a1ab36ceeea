#!/usr/bin/env bash
# The recorder and the replay at the full demo load (issue 19, docs/recording.md): the demo
# scenario (leader, follower, twin at 1 kHz, every topic) runs for SECONDS while `teleop record`
# takes every topic; then the recording is replayed onto an empty domain. Prints the recorder's
# samples, bytes, drops, upstream gaps and CPU, and the replay's timing errors. A benchmark, not a
# test: the numbers depend on the machine and its load.
# Usage: bench/record_replay_bench.sh [SECONDS (default 20)] [DOMAIN (default 150)]
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-20}
domain=${2:-150}
bin=build/default/bin
out=$(mktemp -d /tmp/teleop-record-bench-XXXXXX)
"$bin/teleop" record -o "$out/bag" --domain "$domain" --duration $((seconds + 4)) > "$out/record.txt" 2> "$out/record.log" &
recorder=$!
sleep 1
"$bin/teleop" launch config/scenarios/demo.yaml --domain "$domain" --duration "$seconds" --report-dir "$out/reports" \
  > "$out/launch.txt" 2>&1
wait "$recorder"
echo "== record: the demo for ${seconds} s, every topic"
cat "$out/record.txt"
bytes=$(stat -c %s "$out/bag/bag_0.db3")
echo "database: $bytes bytes, $(awk -v b="$bytes" -v s="$seconds" 'BEGIN { printf "%.0f", b / s }') bytes/s of demo"
sqlite3 "$out/bag/bag_0.db3" \
  "select t.name, count(*) from messages m join topics t on t.id = m.topic_id group by t.name order by t.name"
echo "== replay: everything, onto an empty domain"
"$bin/teleop" replay "$out/bag" --domain $((domain + 1)) --wait-for-readers 0 2> /dev/null
echo "(recording and reports in $out)"
