// The checks of the buses, devices and networks the nodes use, and of what the .deb provisions
// (checks.h).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "teleop/doctor/checks.h"

namespace teleop::doctor {
namespace {

const CanLink* link_named(const std::vector<CanLink>& links, const std::string& name) {
  const auto it = std::find_if(links.begin(), links.end(), [&](const CanLink& l) { return l.name == name; });
  return it == links.end() ? nullptr : &*it;
}

std::string bring_up(const CanNeed& need) {
  char bitrate[32];
  std::snprintf(bitrate, sizeof(bitrate), "%.0f", need.bitrate_bps);
  return "sudo ip link set " + need.interface + " type can bitrate " + bitrate + " restart-ms 100 && sudo ip link set " +
         need.interface + " up (at boot: teleop-can@" + need.interface + ".service, docs/provisioning.md)";
}

Finding check_can_link(const CanLink* link, const CanNeed& need) {
  const std::string check = need.interface;
  const std::string whose = " (" + need.node + ", " + need.file + ")";
  if (link != nullptr && !link->error.empty()) {
    return {check, Verdict::kFail, "could not be looked at" + whose + ": " + link->error,
            "install iproute2 (ip -details -json link)"};
  }
  if (link == nullptr || !link->exists) {
    return {check, Verdict::kFail, "no such interface" + whose,
            "connect the adapter, or for a virtual bus: sudo modprobe vcan && sudo ip link add " + need.interface +
                " type vcan && sudo ip link set " + need.interface + " up"};
  }
  if (link->kind != "can" && link->kind != "vcan") {
    return {check, Verdict::kFail, "a " + (link->kind.empty() ? std::string("plain") : link->kind) +
                                       " link, not a CAN interface" + whose, "name the CAN interface in the config"};
  }
  if (!link->up) {
    return {check, Verdict::kFail, link->kind + ", down" + whose,
            link->kind == "vcan" ? "sudo ip link set " + need.interface + " up" : bring_up(need)};
  }
  if (link->kind == "vcan") return {check, Verdict::kOk, "vcan, up (a virtual bus: no bitrate)", ""};
  const std::string state = link->state.empty() ? "" : ", " + link->state;
  if (std::llround(need.bitrate_bps) != static_cast<long long>(link->bitrate_bps)) {
    return {check, Verdict::kFail,
            "can, up at " + std::to_string(link->bitrate_bps) + " bit/s, the config plans " +
                std::to_string(std::llround(need.bitrate_bps)) + whose,
            "sudo ip link set " + need.interface + " down && " + bring_up(need)};
  }
  if (link->state == "BUS-OFF" || link->state == "STOPPED") {
    return {check, Verdict::kFail, "can, up at " + std::to_string(link->bitrate_bps) + " bit/s" + state,
            "check the wiring and termination (120 ohm at both ends), then: sudo ip link set " + need.interface +
                " type can restart"};
  }
  const Verdict verdict = link->state == "ERROR-PASSIVE" ? Verdict::kWarn : Verdict::kOk;
  return {check, verdict, "can, up at " + std::to_string(link->bitrate_bps) + " bit/s" + state,
          verdict == Verdict::kOk ? "" : "errors on the bus: check the wiring and termination (120 ohm at both ends)"};
}

bool has_address(const std::vector<NetworkInterfaceFacts>& interfaces, const std::string& address) {
  return std::any_of(interfaces.begin(), interfaces.end(),
                     [&](const NetworkInterfaceFacts& i) { return i.up && i.ipv4 == address; });
}

}  // namespace

std::vector<Finding> check_can(const std::vector<CanLink>& links, const HostNeeds& needs) {
  std::vector<Finding> findings;
  for (const CanNeed& need : needs.can) findings.push_back(check_can_link(link_named(links, need.interface), need));
  return findings;
}

Finding check_input_devices(const std::vector<InputDeviceFacts>& devices, const ProvisioningFacts& provisioning) {
  // the devices 60-teleop.rules hands to the group teleop are the operator's: each must be
  // readable and writable (force feedback, LEDs); a keyboard is none of the doctor's business
  std::string usable, unusable;
  for (const InputDeviceFacts& d : devices) {
    if (d.group != "teleop") continue;
    std::string& list = d.readable && d.writable ? usable : unusable;
    list += (list.empty() ? "" : ", ") + d.name + " (" + d.path + ")";
  }
  if (!unusable.empty()) {
    return {"input devices", Verdict::kWarn, "not usable by " + provisioning.user + ": " + unusable,
            "sudo usermod -aG teleop " + provisioning.user + ", then log in again"};
  }
  if (!usable.empty()) return {"input devices", Verdict::kOk, usable, ""};
  return {"input devices", Verdict::kOk,
          "no operator device connected (" + std::to_string(devices.size()) +
              " other input devices; the simulated devices need none)",
          ""};
}

std::vector<Finding> check_dds(const std::vector<NetworkInterfaceFacts>& interfaces, const HostNeeds& needs) {
  std::vector<Finding> findings;
  std::string outward;
  bool multicast = false;
  for (const NetworkInterfaceFacts& i : interfaces) {
    if (!i.up || i.loopback || i.ipv4.empty()) continue;
    outward += (outward.empty() ? "" : ", ") + i.name + " " + i.ipv4 + (i.multicast ? " (multicast)" : "");
    multicast = multicast || i.multicast;
  }
  const bool wants_multicast = std::any_of(needs.dds.begin(), needs.dds.end(),
                                           [](const DdsNeed& d) { return d.multicast_discovery; });
  if (outward.empty()) {
    findings.push_back({"dds", Verdict::kWarn, "only loopback is up: nodes on this host find each other, no other host's",
                        "bring up the lab network's interface"});
  } else if (wants_multicast && !multicast) {
    findings.push_back({"dds", Verdict::kWarn, outward + ": none multicast, which discovery: multicast needs",
                        "discovery: peers or server in the transport section (docs/transport.md)"});
  } else {
    findings.push_back({"dds", Verdict::kOk, outward, ""});
  }
  for (const DdsNeed& need : needs.dds) {
    for (const std::string& address : need.interface_whitelist) {
      if (has_address(interfaces, address)) continue;
      findings.push_back({"dds " + need.node, Verdict::kFail,
                          "interface_whitelist names " + address + " (" + need.file + "), on no interface that is up",
                          "the address of this host's lab interface in transport.interface_whitelist"});
    }
  }
  return findings;
}

Finding check_provisioning(const ProvisioningFacts& provisioning) {
  std::string missing;
  const auto note = [&](bool present, const char* what) {
    if (!present) missing += (missing.empty() ? "" : ", ") + std::string(what);
  };
  note(provisioning.limits_file, "/etc/security/limits.d/95-teleop.conf");
  note(provisioning.udev_rules, "60-teleop.rules");
  note(provisioning.node_unit, "teleop-node@.service");
  note(provisioning.group_exists, "the group teleop");
  if (!missing.empty()) {
    return {"provisioning", Verdict::kWarn, "missing " + missing,
            "sudo apt install ./teleop_<version>_amd64.deb (scripts/package.sh makes it; docs/provisioning.md)"};
  }
  if (!provisioning.in_group) {
    return {"provisioning", Verdict::kWarn, "installed, but " + provisioning.user + " is not in the group teleop",
            "sudo usermod -aG teleop " + provisioning.user + ", then log in again"};
  }
  return {"provisioning", Verdict::kOk, "limits, udev rules and units installed; " + provisioning.user + " in teleop",
          ""};
}

std::vector<Finding> check_host(const HostFacts& facts, const HostNeeds& needs) {
  std::vector<Finding> findings = {
      check_kernel(facts.kernel),
      check_rtprio(facts.scheduling, needs),
      check_memlock(facts.scheduling, needs),
      check_rt_throttling(facts.scheduling),
      check_governors(facts.cpu),
      check_clock(facts.clock),
  };
  for (Finding& f : check_can(facts.can_links, needs)) findings.push_back(std::move(f));
  findings.push_back(check_input_devices(facts.input_devices, facts.provisioning));
  for (Finding& f : check_dds(facts.interfaces, needs)) findings.push_back(std::move(f));
  findings.push_back(check_provisioning(facts.provisioning));
  return findings;
}

}  // namespace teleop::doctor
