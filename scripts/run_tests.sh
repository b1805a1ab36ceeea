#!/usr/bin/env bash
# Sets up (installs missing Debian packages), builds and runs the whole test suite: a normal
# build, then an ASan+UBSan build, then ThreadSanitizer on the threaded core (transport with its
# impairment, runtime; `cmake --workflow --preset tsan` adds the nodes' units, 10 minutes more).
# Fails on the first failing test.
set -euo pipefail
cd "$(dirname "$0")/.."

./scripts/setup.sh
cmake --workflow --preset default
cmake --workflow --preset asan
cmake --workflow --preset tsan-core
