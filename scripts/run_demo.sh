#!/usr/bin/env bash
# Sets up (installs missing Debian packages), builds, and runs the main job: the stiff-wall
# experiment (docs/architectures.md) with PFC+TDPA and model-mediated teleoperation under the
# 35 ms round-trip profile: leader, follower and twin as processes on this host, a simulated
# operator pushing the follower into a wall through a simulated haptic arm. Prints the
# comparison table and where the CSV and the traces are.
# Extra arguments go to `teleop experiment`, e.g. --profiles lan,wan-35ms or --runs pfc,pfc_tdpa.
set -euo pipefail
cd "$(dirname "$0")/.."
export CCACHE_BASEDIR="$PWD" CCACHE_NOHASHDIR=true  # a clone in any folder reuses ccache (run_tests.sh)

# only what the demo needs: its packages, and the CLI with the three nodes (no tests, no benchmarks)
./scripts/setup.sh --demo
cmake --preset demo
cmake --build --preset demo
exec ./build/demo/bin/teleop experiment config/experiments/stiff_wall.yaml --runs pfc_tdpa,mmt --profiles wan-35ms "$@"
