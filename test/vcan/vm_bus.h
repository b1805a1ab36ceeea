#pragma once
// A test's own participant on the VM's bus: UDP on loopback with unicast discovery, since the
// VM's loopback has no multicast (the nodes under test are told the same with --set).

#include <string>

#include "teleop/transport/participant_config.h"

namespace teleop::test {

inline transport::ParticipantConfig vm_participant(int domain, const std::string& name) {
  transport::ParticipantConfig c;
  c.domain_id = domain;
  c.name = name;
  c.udpv4 = true;
  c.shm = false;
  c.interface_whitelist = {"127.0.0.1"};
  c.initial_peers = {"127.0.0.1"};
  c.discovery = transport::DiscoveryMode::kPeers;
  return c;
}

}  // namespace teleop::test
