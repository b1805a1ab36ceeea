#!/bin/busybox sh
# /init of the vcan test VM (see run_in_vm.sh): CAN modules, vcan0..vcan3, the test command, result.
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
# vcan0 for the hand; vcan0..vcan3 for the arm's four buses (two drives per bus at 1 kHz)
for i in 0 1 2 3; do
  ip link add dev vcan$i type vcan || result FAIL 91
  ip link set up vcan$i || result FAIL 92
done
echo "TELEOP_VCAN_BEGIN uptime=$(cut -d' ' -f1 /proc/uptime)s"
sh /opt/teleop/cmd.sh
rc=$?
if [ "$rc" -eq 0 ]; then result PASS 0; else result FAIL "$rc"; fi
