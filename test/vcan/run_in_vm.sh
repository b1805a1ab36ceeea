#!/usr/bin/env bash
# Runs a test command where a vcan interface exists.
#   run_in_vm.sh [--cache DIR] [--timeout S] [--vm] --bin FILE [--bin FILE ...] [--data DIR ...] -- COMMAND [ARGS...]
# Host with vcan (root, `ip link add type vcan` works): creates four private vcan interfaces, runs
# COMMAND directly with the --bin folders on PATH, TELEOP_VCAN_IF (the first) and TELEOP_VCAN_IFS
# (all four) set, deletes the interfaces.
# Otherwise: boots Debian's kernel in qemu (TCG is fine) from an initramfs holding busybox, the
# CAN and input (evdev, uinput) modules, iproute2's ip, candump/cansend, the --bin files and every library ldd lists;
# inside, loads can, can-raw, can-dev, vcan, creates vcan0..vcan3, runs COMMAND (the --data folders in
# /opt/teleop/share/teleop/, where the binaries in /opt/teleop/bin look for teleop's data), prints
# "TELEOP_VCAN_RESULT PASS|FAIL rc=N" on the serial console and powers off. This script exits
# with COMMAND's status; with 1 when anything is missing (never skips) or no result came back
# within the timeout. The kernel package and the base initramfs are cached under --cache and
# rebuilt only when their inputs change. TELEOP_QEMU overrides the qemu binary.
set -euo pipefail

cache=""
timeout_s=180
bins=()
datas=()
force_vm=0
while [ $# -gt 0 ]; do
  case "$1" in
    --cache) cache="$2"; shift 2 ;;
    --timeout) timeout_s="$2"; shift 2 ;;
    --bin) bins+=("$2"); shift 2 ;;
    --data) datas+=("$2"); shift 2 ;;
    --vm) force_vm=1; shift ;;
    --) shift; break ;;
    *) echo "run_in_vm: unknown argument $1" >&2; exit 2 ;;
  esac
done
[ $# -gt 0 ] || { echo "run_in_vm: no command given (after --)" >&2; exit 2; }
die() { echo "run_in_vm: FAIL: $*" >&2; exit 1; }
for b in "${bins[@]}"; do [ -x "$b" ] || die "test binary $b missing or not executable"; done
for d in "${datas[@]}"; do [ -d "$d" ] || die "data folder $d missing"; done
start_ns=$(date +%s%N)
elapsed() { echo "$(( ($(date +%s%N) - start_ns) / 1000000 )) ms"; }

# --- 1. the host has vcan: run directly -----------------------------------------------------
if [ "$force_vm" -eq 0 ] && [ "$(id -u)" -eq 0 ] && command -v ip >/dev/null; then
  probe="tvcan$$"
  if ip link add dev "$probe" type vcan 2>/dev/null; then
    # three more for the arm's four buses (TELEOP_VCAN_IFS; the VM's are vcan0..vcan3)
    probes="$probe"
    for i in 1 2 3; do ip link add dev "$probe-$i" type vcan && probes="$probes $probe-$i"; done
    trap 'for p in $probes; do ip link del dev "$p" 2>/dev/null || true; done' EXIT
    for p in $probes; do ip link set up "$p"; done
    path_add=""
    for b in "${bins[@]}"; do path_add="$path_add$(cd "$(dirname "$b")" && pwd):"; done
    echo "run_in_vm: host kernel has vcan: running directly on $probe"
    set +e
    PATH="$path_add$PATH" TELEOP_VCAN_IF="$probe" TELEOP_VCAN_IFS="$probes" "$@"
    rc=$?
    set -e
    echo "run_in_vm: direct run rc=$rc after $(elapsed)"
    exit $rc
  fi
fi

# --- 2. qemu ----------------------------------------------------------------------------------
[ -n "$cache" ] || cache="${TMPDIR:-/tmp}/teleop-vcan-vm"
mkdir -p "$cache"
cache=$(cd "$cache" && pwd)
qemu=${TELEOP_QEMU:-qemu-system-x86_64}
command -v "$qemu" >/dev/null || die "$qemu not found (scripts/setup.sh installs qemu-system-x86)"
busybox=$(command -v busybox || true)
[ -n "$busybox" ] || die "busybox not found (busybox-static)"
file -L "$busybox" 2>/dev/null | grep -q "statically linked" || ldd "$busybox" 2>&1 | grep -q "not a dynamic" ||
  die "$busybox is not static (install busybox-static)"
ipbin=$(command -v ip || echo /usr/sbin/ip); [ -x "$ipbin" ] || die "iproute2's ip not found"
candump=$(command -v candump || true); cansend=$(command -v cansend || true)
[ -n "$candump" ] && [ -n "$cansend" ] || die "candump/cansend not found (can-utils)"
command -v cpio >/dev/null || die "cpio not found"

# the kernel: linux-image-amd64's dependency, downloaded once into the cache
# (a package already in the cache is used as it is: delete the cache to follow a kernel update)
kpkg=$(cd "$cache" && ls linux-image-*-amd64_*.deb 2>/dev/null | head -1 | cut -d_ -f1 || true)
[ -n "$kpkg" ] || kpkg=$(apt-cache depends linux-image-amd64 2>/dev/null | awk '/Depends: linux-image-[0-9]/{print $2; exit}')
[ -n "$kpkg" ] || die "cannot tell the kernel package (apt-cache depends linux-image-amd64 found nothing)"
deb=$(ls "$cache"/"${kpkg}"_*.deb 2>/dev/null | head -1 || true)
if [ -z "$deb" ]; then
  echo "run_in_vm: downloading $kpkg"
  (cd "$cache" && apt-get download "$kpkg" >/dev/null 2>&1) || cp /var/cache/apt/archives/"${kpkg}"_*.deb "$cache"/ 2>/dev/null ||
    die "cannot download kernel package $kpkg (apt-get download $kpkg)"
  deb=$(ls "$cache"/"${kpkg}"_*.deb | head -1)
fi
# keep only what the VM needs (the whole package extracts to ~400 MB)
kdir="$cache/kernel-$(basename "$deb" .deb)"
kmods=(net/can/can.ko net/can/can-raw.ko drivers/net/can/dev/can-dev.ko drivers/net/can/vcan.ko
  drivers/input/evdev.ko drivers/input/misc/uinput.ko)
if [ ! -f "$kdir/.done" ] || [ ! -f "$kdir/vmlinuz" ] || [ "$(cat "$kdir/.done")" != "${kmods[*]}" ]; then
  rm -rf "$kdir" "$kdir.x"; mkdir -p "$kdir/modules" "$kdir.x"
  dpkg-deb -x "$deb" "$kdir.x" || die "cannot extract $deb"
  cp "$(ls "$kdir.x"/boot/vmlinuz-* | head -1)" "$kdir/vmlinuz" || die "no vmlinuz in $deb"
  moddir=$(ls -d "$kdir.x"/lib/modules/*/ | head -1)
  n=0
  for m in "${kmods[@]}"; do
    f=$(ls "$moddir/kernel/$m"* 2>/dev/null | head -1 || true)
    [ -n "$f" ] || { rm -rf "$kdir" "$kdir.x"; die "module $m missing in $deb"; }
    n=$((n + 1))
    cp "$f" "$kdir/modules/$n-$(basename "$f")"  # numbered: insmod order can, can-raw, can-dev, vcan, evdev, uinput
  done
  rm -rf "$kdir.x"
  echo "${kmods[*]}" > "$kdir/.done"  # the modules it holds: a changed list extracts again
fi
vmlinuz="$kdir/vmlinuz"

# copies a binary and its ldd libraries into root $1 (binary into $3): the system's at their own
# paths, the others (teleop's, from the build tree) into /opt/teleop/lib, which cmd.sh puts on
# LD_LIBRARY_PATH: a build tree under /tmp would be hidden by the tmpfs the guest mounts there
add_elf() {
  local root=$1 src=$2 dst=$3
  mkdir -p "$root$(dirname "$dst")"
  cp -L "$src" "$root$dst"
  local lib to
  for lib in $(ldd "$src" 2>/dev/null | grep -o '/[^ ]*' || true); do
    case "$lib" in
      /lib/* | /lib64/* | /usr/lib/* | /usr/lib64/*) to=$lib ;;
      *) to=/opt/teleop/lib/$(basename "$lib") ;;
    esac
    [ -e "$root$to" ] && continue
    mkdir -p "$root$(dirname "$to")"
    cp -L "$lib" "$root$to"
  done
}

# base image: busybox, modules, ip, can-utils, /init; keyed by everything that goes into it
init_src="$(cd "$(dirname "$0")" && pwd)/vm_init.sh"
[ -f "$init_src" ] || die "$init_src missing"
key=$({ basename "$deb"; stat -c '%s' "$deb"; sha256sum "$busybox" "$ipbin" "$candump" "$cansend" "$init_src" "$0"; } |
  sha256sum | cut -c1-16)
base="$cache/base-$key.cpio.gz"
if [ ! -f "$base" ]; then
  echo "run_in_vm: building base initramfs"
  rm -f "$cache"/base-*.cpio.gz
  root="$cache/base-root"; rm -rf "$root"
  mkdir -p "$root"/{bin,sbin,proc,sys,dev,tmp,etc,lib/modules,opt/teleop/bin}
  cp "$busybox" "$root/bin/busybox"
  cp "$init_src" "$root/init"; chmod 755 "$root/init"
  cp "$kdir"/modules/*.ko "$root/lib/modules/"
  add_elf "$root" "$ipbin" /opt/teleop/bin/ip
  add_elf "$root" "$candump" /opt/teleop/bin/candump
  add_elf "$root" "$cansend" /opt/teleop/bin/cansend
  (cd "$root" && find . | cpio -o -H newc --quiet | gzip -1) > "$base.tmp"
  mv "$base.tmp" "$base"
  rm -rf "$root"
fi

# payload: the test binaries and the command, appended as a second cpio archive
work=$(mktemp -d "$cache/run.XXXXXX")
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/root/opt/teleop/bin"
for b in "${bins[@]}"; do
  add_elf "$work/root" "$b" "/opt/teleop/bin/$(basename "$b")"
  # debug info only makes the initramfs big and slow to pack
  strip --strip-debug "$work/root/opt/teleop/bin/$(basename "$b")" 2>/dev/null || true
done
# data: where an installed teleop has it, beside its bin/ (teleop::find_data)
for d in "${datas[@]}"; do
  mkdir -p "$work/root/opt/teleop/share/teleop"
  cp -r "$d" "$work/root/opt/teleop/share/teleop/$(basename "$d")"
done
{
  printf 'cd /tmp\n'
  printf 'export LD_LIBRARY_PATH=/opt/teleop/lib\n'
  # the sanitizer options of the test preset (e.g. the ASan build's new_delete_type_mismatch=0,
  # for Fast DDS) hold in the VM too
  for v in ASAN_OPTIONS UBSAN_OPTIONS TSAN_OPTIONS LSAN_OPTIONS; do
    [ -n "${!v:-}" ] && printf 'export %s=%q\n' "$v" "${!v}"
  done
  printf '%q ' "$@"
  printf '\n'
} > "$work/root/opt/teleop/cmd.sh"
(cd "$work/root" && find . | cpio -o -H newc --quiet | gzip -1) > "$work/payload.cpio.gz"
cat "$base" "$work/payload.cpio.gz" > "$work/initrd.gz"

# one VM run: console into $log (echoed), status of qemu in $qrc. Under TCG on a loaded host the
# guest kernel now and then hangs while booting (RCU stalls, a CPU whose timer never fires): a
# guest that has not printed TELEOP_VCAN_BEGIN within boot_timeout_s is killed and booted once
# more, saying so.
log="$work/console.log"
boot_timeout_s=${TELEOP_VCAN_BOOT_TIMEOUT:-90}
run_vm() {
  : > "$log"
  timeout --kill-after=10 "$timeout_s" "$qemu" -m 1536 -smp 2 -nographic -no-reboot \
    -kernel "$vmlinuz" -initrd "$work/initrd.gz" -append "console=ttyS0 quiet panic=-1" \
    < /dev/null > "$log" 2>&1 &
  local qpid=$! waited=0 booted=0
  tail -n +1 -f --pid=$qpid "$log" &
  local tpid=$!
  while kill -0 $qpid 2>/dev/null; do
    if [ $booted -eq 0 ] && grep -q TELEOP_VCAN_BEGIN "$log"; then booted=1; fi
    if [ $booted -eq 0 ] && [ $waited -ge $((boot_timeout_s * 2)) ]; then
      echo "run_in_vm: the guest did not boot within ${boot_timeout_s} s"
      kill $qpid 2>/dev/null || true
      wait $qpid 2>/dev/null || true
      wait $tpid 2>/dev/null || true
      qrc=125
      return 1
    fi
    sleep 0.5
    waited=$((waited + 1))
  done
  wait $qpid
  qrc=$?
  wait $tpid 2>/dev/null || true
  return 0
}
echo "run_in_vm: booting $kpkg in qemu (timeout ${timeout_s} s), initramfs ready after $(elapsed)"
set +e
if ! run_vm; then
  echo "run_in_vm: booting again (once)"
  run_vm || { set -e; die "the guest did not boot within ${boot_timeout_s} s, twice"; }
fi
set -e
result=$(tr -d '\r' < "$log" | grep -o 'TELEOP_VCAN_RESULT [A-Z]* rc=[0-9]*' | tail -1 || true)
if [ -z "$result" ]; then
  [ "$qrc" -eq 124 ] && die "no result within ${timeout_s} s (qemu killed)"
  die "the VM ended without a result marker (qemu status $qrc)"
fi
rc=${result##*rc=}
echo "run_in_vm: $result after $(elapsed) (qemu status $qrc)"
exit "$rc"
