#!/bin/busybox sh
# /init of the vcan test VM (see run_in_vm.sh): CAN modules, vcan0, the test command, result.
/bin/busybox --install -s /bin
export PATH=/opt/teleop/bin:/bin
mount -t proc proc /proc
mount -t sysfs sys /sys
mount -t devtmpfs dev /dev
mount -t tmpfs tmp /tmp
result() {
  echo "TELEOP_VCAN_RESULT $1 rc=$2 uptime=$(cut -d' ' -f1 /proc/uptime)s"
  sync
  poweroff -f
  exit "$2"
}
for m in /lib/modules/*.ko; do
  insmod "$m" || result FAIL 90
done
ip link set lo up
ip link add dev vcan0 type vcan || result FAIL 91
ip link set up vcan0 || result FAIL 92
echo "TELEOP_VCAN_BEGIN uptime=$(cut -d' ' -f1 /proc/uptime)s"
sh /opt/teleop/cmd.sh
rc=$?
if [ "$rc" -eq 0 ]; then result PASS 0; else result FAIL "$rc"; fi
