#!/usr/bin/env bash
# Sets up (installs missing Debian packages), builds and runs the whole test suite twice:
# a normal build, then an ASan+UBSan build. Fails on the first failing test.
set -euo pipefail
cd "$(dirname "$0")/.."

./scripts/setup.sh
cmake --workflow --preset default
cmake --workflow --preset asan
