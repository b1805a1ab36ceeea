#!/usr/bin/env bash
# Installs the Debian 12 packages teleop needs. Idempotent: does nothing when all are present.
#   scripts/setup.sh          everything: build, demo, tests, benchmarks (scripts/run_tests.sh), and
#                             the npm packages of the MCAP and bridge interop tests (into build/npm)
#   scripts/setup.sh --demo   what building and running the demo needs (scripts/run_demo.sh)
set -euo pipefail

# build and run the nodes, the CLI and the demo's figures
# libqhull-dev: Debian's mujoco CMake config names its include folder without depending on it
demo_packages=(
  build-essential cmake ninja-build ccache pkg-config git
  libfastrtps-dev libfastcdr-dev fastddsgen default-jre-headless
  libmujoco-dev libqhull-dev libeigen3-dev libyaml-cpp-dev libspdlog-dev libcli11-dev libssl-dev
  # Debian's mujoco CMake config finds OpenGL (its viewer's); a fresh machine has no GL headers
  libgl-dev libopengl-dev libglx-dev
  # recordings of the bus (bag/, docs/recording.md): sqlite3 bags; MCAP chunks and their CRCs
  libsqlite3-dev libzstd-dev liblz4-dev zlib1g-dev
  # figures of runs and experiments (teleop plot, teleop experiment; docs/plots.md)
  python3-matplotlib
  # the 3D view and videos of runs (teleop view, teleop render; docs/view.md): its window, its PNGs
  libglfw3-dev libpng-dev
  # teleop bridge, the bus in Foxglove/Lichtblick (docs/tools.md): WebSocket server on standalone asio, JSON
  libwebsocketpp-dev libasio-dev nlohmann-json3-dev
  # Linux input devices beside the operator's (leader.button_input: an e-stop button; docs/stop_chain.md)
  libevdev-dev
)
# the test suite and the benchmarks on top
test_packages=(
  libgtest-dev libgmock-dev libbenchmark-dev
  # the discovery server (fastdds discovery) of the discovery tests; sqlite3 to look into a bag
  fastdds-tools sqlite3
  # Cyclone DDS 0.10 (ROS 2's other RMW) and its idlc: the interop test (test/transport/CMakeLists.txt);
  # idlc is in cyclonedds-tools, not in -dev (a fresh machine had the headers and no idlc)
  cyclonedds-dev cyclonedds-tools
  can-utils iproute2
  # the package test (test/install/package_test.sh): systemd-analyze verify of the units against
  # systemd's own targets (a container may lack them)
  systemd
  # multi-host and security tests (test/netns): namespaces, the PKI script, packet capture
  openssl tcpdump
  # vcan HIL harness (test/vcan/run_in_vm.sh): a qemu VM with Debian's kernel and a busybox initramfs
  qemu-system-x86 busybox-static cpio
  # libFuzzer target of the CAN frame decoders and the config parsers: clang and its fuzzer runtime
  clang libclang-rt-14-dev
  # the view's tests (test/integration/view_process_test.cpp): a virtual display with Mesa's software
  # OpenGL, ffmpeg for teleop render's MP4 and ffprobe to check it; xauth for xvfb-run (docs/view.md)
  xvfb xauth libgl1-mesa-dri ffmpeg
)

case "${1:-}" in
  --demo) packages=("${demo_packages[@]}") ;;
  "") packages=("${demo_packages[@]}" "${test_packages[@]}") ;;
  *) echo "usage: $0 [--demo]" >&2; exit 2 ;;
esac

# the reference MCAP readers and the Foxglove WebSocket client of the interop tests
# (test/bag/mcap_interop, test/bridge/ws_interop; one package.json for both): npm packages for the
# tests only, installed into build/npm (never needed to build or run teleop); Debian's nodejs and
# npm when the machine has no node
install_test_npm() {
  local root dest
  root="$(cd "$(dirname "$0")/.." && pwd)"
  dest="$root/build/npm"
  if cmp -s "$root/test/bag/mcap_interop/package-lock.json" "$dest/node_modules/.package-lock.json.source" 2>/dev/null; then
    echo "setup: the interop tests' npm packages present"
    return
  fi
  if ! command -v npm >/dev/null; then
    DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends nodejs npm
  fi
  mkdir -p "$dest"
  cp "$root/test/bag/mcap_interop/package.json" "$root/test/bag/mcap_interop/package-lock.json" "$dest/"
  (cd "$dest" && npm ci --no-audit --no-fund --ignore-scripts --loglevel=error)
  cp "$root/test/bag/mcap_interop/package-lock.json" "$dest/node_modules/.package-lock.json.source"
  echo "setup: the interop tests' npm packages installed into $dest"
}

sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi

missing=()
for pkg in "${packages[@]}"; do
  # a package counts as present only when dpkg reports it fully installed
  if ! dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$pkg")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages present"
else
  echo "setup: installing ${missing[*]}"
  "${sudo_cmd[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
if [ -z "${1:-}" ]; then install_test_npm; fi
