#!/usr/bin/env bash
# Builds what teleop installs (the default preset; no tests, no benchmarks) and makes its Debian
# package: build/default/teleop_<version>_amd64.deb (docs/install.md). Then:
#   sudo apt install ./build/default/teleop_*.deb
# dpkg-shlibdeps (dpkg-dev, with build-essential from scripts/setup.sh) computes its Depends.
set -euo pipefail
cd "$(dirname "$0")/.."

cmake --preset default
cmake --build --preset default --target teleop_installables
cd build/default
cpack -G DEB
dpkg-deb --field teleop_*.deb Package Version Depends Recommends Suggests Installed-Size
ls -l teleop_*.deb
