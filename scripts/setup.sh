#!/usr/bin/env bash
# Installs the Debian 12 packages teleop needs. Idempotent: does nothing when all are present.
set -euo pipefail

# libqhull-dev: Debian's mujoco CMake config names its include folder without depending on it
packages=(
  build-essential cmake ninja-build ccache pkg-config
  libfastrtps-dev libfastcdr-dev fastddsgen fastdds-tools default-jre-headless
  libmujoco-dev libqhull-dev libeigen3-dev libyaml-cpp-dev libspdlog-dev libcli11-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  # recordings of the bus (bag/, docs/recording.md): SQLite, and its shell to look into a bag
  libsqlite3-dev sqlite3
  can-utils iproute2
  # multi-host and security tests (test/netns): namespaces, the PKI script, packet capture
  openssl libssl-dev tcpdump
  # vcan HIL harness (test/vcan/run_in_vm.sh): a qemu VM with Debian's kernel and a busybox initramfs
  qemu-system-x86 busybox-static cpio
  # libFuzzer target of the CAN frame decoders (test/hand/fuzz): clang and its fuzzer runtime
  clang libclang-rt-14-dev
  # figures of runs and experiments (teleop plot, teleop experiment; docs/plots.md)
  python3-matplotlib
)

missing=()
for pkg in "${packages[@]}"; do
  # a package counts as present only when dpkg reports it fully installed
  if ! dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$pkg")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages present"
  exit 0
fi

sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
echo "setup: installing ${missing[*]}"
"${sudo_cmd[@]}" apt-get update -qq
DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
