#pragma once
// What `teleop doctor` knows of a host: everything its checks judge, gathered in one place so a
// test can fake any of it (host_reader.h reads the real host).

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace teleop::doctor {

/// RLIM_INFINITY as a value of ours, so the facts need no <sys/resource.h>.
inline constexpr uint64_t kUnlimited = UINT64_MAX;

struct KernelFacts {
  std::string release;             ///< uname -r
  std::string version;             ///< uname -v ("#1 SMP PREEMPT_RT ...")
  bool realtime_flag = false;      ///< /sys/kernel/realtime reads 1 (a PREEMPT_RT kernel)
  std::string preemption;          ///< /sys/kernel/debug/sched/preempt's choice, when readable
};

struct SchedulingFacts {
  uint64_t rtprio_soft = 0;        ///< RLIMIT_RTPRIO
  uint64_t memlock_soft = 0;       ///< RLIMIT_MEMLOCK [bytes]
  bool cap_sys_nice = false;       ///< CAP_SYS_NICE in the effective set: no rtprio limit applies
  bool cap_ipc_lock = false;       ///< CAP_IPC_LOCK: no memlock limit applies
  /// What SCHED_FIFO at the priority the configs ask for answered when tried on a thread of
  /// ours (empty: it worked; nullopt: not tried).
  std::optional<std::string> fifo_trial;
  int fifo_trial_priority = 0;
  int64_t rt_runtime_us = 950000;  ///< /proc/sys/kernel/sched_rt_runtime_us (-1: no throttling)
  int64_t rt_period_us = 1000000;
};

struct CpuFacts {
  /// scaling_governor of each CPU that has cpufreq, in CPU order; empty: no cpufreq (a VM, or a
  /// fixed frequency).
  std::vector<std::string> governors;
};

struct ClockFacts {
  bool synchronised = false;       ///< adjtimex: no STA_UNSYNC, not TIME_ERROR
  int64_t max_error_us = 0;        ///< adjtimex maxerror
  int64_t estimated_error_us = 0;  ///< adjtimex esterror
  /// The time daemons running (chronyd, ptp4l, phc2sys, systemd-timesyncd, ntpd), by name.
  std::vector<std::string> daemons;
};

/// A network interface as the configs' CAN buses need it (from `ip -details -json link`).
struct CanLink {
  std::string name;
  bool exists = false;
  std::string kind;                ///< "can", "vcan", or another link kind
  bool up = false;
  uint64_t bitrate_bps = 0;        ///< 0: none set (vcan has none)
  std::string state;               ///< the controller's state: ERROR-ACTIVE, BUS-OFF, ...
  std::string error;               ///< why `ip` could not say ("" when it did)
};

struct InputDeviceFacts {
  std::string path;                ///< /dev/input/event3
  std::string name;                ///< what the device calls itself
  std::string group;               ///< the device node's group: "teleop" for what 60-teleop.rules grants
  bool readable = false;
  bool writable = false;           ///< force feedback and LEDs need it
};

struct NetworkInterfaceFacts {
  std::string name;
  std::string ipv4;                ///< its first IPv4 address, "" when none
  bool up = false;
  bool loopback = false;
  bool multicast = false;
};

/// What the .deb installs for a lab's machine (docs/provisioning.md).
struct ProvisioningFacts {
  bool limits_file = false;        ///< /etc/security/limits.d/95-teleop.conf
  bool udev_rules = false;         ///< 60-teleop.rules in /usr/lib/udev/rules.d or /etc/udev/rules.d
  bool node_unit = false;          ///< teleop-node@.service
  bool group_exists = false;       ///< the `teleop` group
  bool in_group = false;           ///< this user is in it (effective now, not only in /etc/group)
  std::string user;
};

struct HostFacts {
  KernelFacts kernel;
  SchedulingFacts scheduling;
  CpuFacts cpu;
  ClockFacts clock;
  std::vector<CanLink> can_links;  ///< one per interface a config names, in the configs' order
  std::vector<InputDeviceFacts> input_devices;
  std::vector<NetworkInterfaceFacts> interfaces;
  ProvisioningFacts provisioning;
};

}  // namespace teleop::doctor
