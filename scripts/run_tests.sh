#!/usr/bin/env bash
# Sets up (installs missing Debian packages), builds and runs the whole test suite: a normal
# build, then an ASan+UBSan build, then ThreadSanitizer on the threaded core (transport with its
# impairment, runtime; `cmake --workflow --preset tsan` adds the nodes' units, 10 minutes more).
# Fails on the first failing test.
set -euo pipefail
cd "$(dirname "$0")/.."
# ccache (the presets use it when installed) keys what it compiled on paths relative to the clone,
# so a fresh clone in any folder reuses what a build of the same sources compiled before: without
# this a clone outside ccache's configured base_dir compiled all three builds again, and CI ran out
# of its 90 minutes
export CCACHE_BASEDIR="$PWD" CCACHE_NOHASHDIR=true

# each stage's wall time, so a run's budget (CI: 60 min on 2 cores) is visible stage by stage
stage() {
  local name=$1 start=$SECONDS
  shift
  "$@" || { failure_digest "$name"; exit 1; }
  echo "run_tests: stage $name took $((SECONDS - start)) s (total $SECONDS s)"
}

# A failed test's output can run to thousands of lines (the VM's console holds six executables)
# and a CI excerpt keeps only its head and the run's tail: what failed is said again, last.
failure_digest() {
  local log="build/$1/Testing/Temporary/LastTest.log"
  [ -f "$log" ] || return 0
  echo "run_tests: stage $1 failed; its failures, again:"
  grep -a -A6 -E '^[^ ].*: Failure$|^==[0-9]+==ERROR: |runtime error: ' "$log" | head -150 || true
  grep -a -E '^\[  FAILED  \] [^ ]+ \(' "$log" | sort -u || true
}

stage setup ./scripts/setup.sh
stage default cmake --workflow --preset default
stage asan cmake --workflow --preset asan
stage tsan-core cmake --workflow --preset tsan-core
