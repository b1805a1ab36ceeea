#!/usr/bin/env bash
# The soak's long form (issue 16, docs/reliability.md): leader, twin and follower of the
# model-mediated stiff wall, each killed with SIGKILL and started again 50 times at random, over
# the network of config/network/soak.yaml (35 ms, 50 % bursty loss, outages). About 20 minutes.
# Options go to `teleop soak` (e.g. --kills-per-node 10, --seed 3, --report-dir DIR).
set -euo pipefail
cd "$(dirname "$0")/.."
if [ ! -x build/default/bin/teleop ]; then
  ./scripts/setup.sh
  cmake --preset default
  cmake --build --preset default --target teleop teleop_leader teleop_follower teleop_twin
fi
exec build/default/bin/teleop soak config/experiments/soak.yaml --kills-per-node 50 "$@"
