#!/usr/bin/env bash
# The Debian package a lab installs (docs/provisioning.md): built by cpack from this build into a
# folder of its own, it must hold the provisioning files at the system's paths with the two in
# /etc as conffiles and working maintainer scripts; its units must pass systemd-analyze verify
# against the package's own tree; and `teleop doctor --root` on that tree must find them.
#   package_test.sh BUILD_DIR
set -euo pipefail
build=$1
fail() { echo "package_test: FAIL: $*" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

cpack=$(dirname "$(command -v cmake)")/cpack
(cd "$build" && "$cpack" -G DEB -B "$work/out" >"$work/cpack.log" 2>&1) || { cat "$work/cpack.log"; fail "cpack"; }
deb=$(ls "$work"/out/teleop_*.deb)
echo "package_test: $(basename "$deb")"

dpkg-deb -c "$deb" | awk '{print $6}' | sed 's|^\./|/|' > "$work/files"
for f in /etc/security/limits.d/95-teleop.conf /etc/teleop/can/can0.conf /usr/lib/udev/rules.d/60-teleop.rules \
         /usr/lib/systemd/system/teleop-node@.service /usr/lib/systemd/system/teleop-can@.service \
         /usr/lib/systemd/system/teleop.slice /usr/share/doc/teleop/provisioning.md /usr/bin/teleop; do
  grep -qx "$f" "$work/files" || fail "$f not in the package"
  echo "package_test: has $f"
done

dpkg-deb -e "$deb" "$work/control"
diff <(sort "$work/control/conffiles") <(printf '%s\n' /etc/security/limits.d/95-teleop.conf /etc/teleop/can/can0.conf) ||
  fail "conffiles"
for s in postinst postrm; do
  [ -x "$work/control/$s" ] || fail "$s not executable"
  sh -n "$work/control/$s" || fail "$s does not parse"
done
grep -q '^Depends: adduser' <(dpkg-deb --field "$deb") || fail "the postinst's adduser is not a dependency"
# the postinst on a host without the user: it makes the group, then the system user in it
stubs="$work/stubs"; mkdir -p "$stubs"
for tool in getent addgroup adduser udevadm systemctl; do
  printf '#!/bin/sh\necho "%s $*" >> "%s"\n[ %s != getent ] || exit 2\n' "$tool" "$work/calls" "$tool" > "$stubs/$tool"
  chmod +x "$stubs/$tool"
done
PATH="$stubs:$PATH" sh "$work/control/postinst" configure || fail "postinst configure"
grep -qx 'addgroup --system teleop' "$work/calls" || fail "postinst made no group: $(cat "$work/calls")"
grep -q '^adduser --system --ingroup teleop .* teleop$' "$work/calls" || fail "postinst made no user: $(cat "$work/calls")"
echo "package_test: postinst: $(tr '\n' ';' < "$work/calls")"

# the units against the package's tree: the systemd targets they name, and ip for the CAN unit
root="$work/root"
dpkg-deb -x "$deb" "$root"
[ -f /usr/lib/systemd/system/sysinit.target ] || fail "systemd's units missing (scripts/setup.sh installs systemd)"
cp -n /usr/lib/systemd/system/*.target /usr/lib/systemd/system/*.slice "$root/usr/lib/systemd/system/"
mkdir -p "$root/usr/sbin" && cp "$(command -v ip)" "$root/usr/sbin/ip"
verify=$(systemd-analyze verify --man=no --root="$root" teleop-node@follower.service teleop-can@can0.service 2>&1) ||
  fail "systemd-analyze verify: $verify"
[ -z "$verify" ] || fail "systemd-analyze verify: $verify"
echo "package_test: the units verify"

# the doctor sees what the package put there (the group exists only once the postinst ran)
doctor=$("$build/bin/teleop" doctor --root "$root" 2>&1) || true
line=$(grep '  provisioning ' <<<"$doctor") || fail "no provisioning line: $doctor"
for f in 95-teleop.conf 60-teleop.rules teleop-node@.service; do
  ! grep -q "$f" <<<"$line" || fail "the doctor misses $f in the package's tree: $line"
done
echo "package_test: doctor:$line"
echo "package_test: PASS"
