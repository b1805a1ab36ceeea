#pragma once
// The doctor's checks: each judges some of a host's facts against what the node configs need and
// says how to fix a miss. Pure functions of HostFacts and HostNeeds, so each is tested on faked
// facts (test/doctor/), and the same code judges the real host (host_reader.h).

#include <vector>

#include "teleop/doctor/finding.h"
#include "teleop/doctor/host_facts.h"
#include "teleop/doctor/host_needs.h"

namespace teleop::doctor {

// scheduling (realtime_checks.cpp)
Finding check_kernel(const KernelFacts& kernel);
Finding check_rtprio(const SchedulingFacts& scheduling, const HostNeeds& needs);
Finding check_memlock(const SchedulingFacts& scheduling, const HostNeeds& needs);
Finding check_rt_throttling(const SchedulingFacts& scheduling);
Finding check_governors(const CpuFacts& cpu);
Finding check_clock(const ClockFacts& clock);

// devices and networks (device_checks.cpp)
/// One finding per CAN bus the configs name; `links` holds what `ip` said of each.
std::vector<Finding> check_can(const std::vector<CanLink>& links, const HostNeeds& needs);
Finding check_input_devices(const std::vector<InputDeviceFacts>& devices, const ProvisioningFacts& provisioning);
std::vector<Finding> check_dds(const std::vector<NetworkInterfaceFacts>& interfaces, const HostNeeds& needs);
Finding check_provisioning(const ProvisioningFacts& provisioning);

/// Every check, in the order the doctor prints them.
std::vector<Finding> check_host(const HostFacts& facts, const HostNeeds& needs);

}  // namespace teleop::doctor
