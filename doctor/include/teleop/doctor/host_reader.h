#pragma once
// Reads the facts `teleop doctor` judges from this host: files under /proc, /sys, /dev and /etc
// (under `root`, which a test points at a tree of its own), the process's limits and
// capabilities, adjtimex, the network interfaces, and `ip -details -json link` for CAN buses.

#include <string>
#include <vector>

#include "teleop/doctor/host_facts.h"
#include "teleop/doctor/host_needs.h"

namespace teleop::doctor {

/// Everything, for the buses and the priority `needs` names; tries SCHED_FIFO on a thread.
HostFacts read_host(const HostNeeds& needs, const std::string& root = "/");

// the parts read from files, each testable on a tree of its own
KernelFacts read_kernel(const std::string& root);
/// scaling_governor of root/sys/devices/system/cpu/cpuN, in CPU order.
std::vector<std::string> read_governors(const std::string& root);
/// The time daemons among root/proc/<pid>/comm.
std::vector<std::string> read_time_daemons(const std::string& root);
/// root/dev/input/event*, named from root/sys/class/input/eventN/device/name.
std::vector<InputDeviceFacts> read_input_devices(const std::string& root);
/// The provisioning files under root; the group and its membership from this process.
ProvisioningFacts read_provisioning(const std::string& root);

/// One interface out of `ip -details -json link show dev NAME`'s answer ("" or not JSON: it
/// does not exist). Throws std::runtime_error for JSON that is not ip's.
CanLink parse_ip_link(const std::string& name, const std::string& ip_json);
/// Asks `ip` (iproute2); what ip answers other than "does not exist" is kept in CanLink::error.
CanLink read_can_link(const std::string& name);

}  // namespace teleop::doctor
