#!/usr/bin/env bash
# Sets up (installs missing Debian packages), builds, and runs the main job: the demo scenario
# (leader, follower and twin on this host), ending with the run summary.
# Extra arguments go to `teleop launch`, e.g. --duration 10.
set -euo pipefail
cd "$(dirname "$0")/.."

./scripts/setup.sh
cmake --preset default
cmake --build --preset default
exec ./build/default/bin/teleop launch config/scenarios/demo.yaml "$@"
