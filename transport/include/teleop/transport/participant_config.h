#pragma once
// How a node joins the DDS domain: domain, transports, peers, leases.

#include <cstdint>
#include <string>
#include <vector>

#include "teleop/common/config.h"
#include "teleop/transport/impairment/impairment_config.h"

namespace teleop::transport {

struct ParticipantConfig {
  int domain_id = 0;
  /// Participant name shown in discovery tools.
  std::string name = "teleop";
  /// Network transport; needed for anything that leaves this host.
  bool udpv4 = true;
  /// Shared-memory transport between processes on one host: lower latency, but Fast DDS 2.9
  /// allocates three times per sent sample in it (measured), so it is off by default.
  bool shm = false;
  /// Unicast discovery peers, "address" or "address:port" (port 0 / absent: the domain's
  /// well-known discovery ports). Lets nodes find each other where multicast is not allowed.
  std::vector<std::string> initial_peers;
  /// Network interfaces (IPv4 addresses) UDP may use; empty = all.
  std::vector<std::string> interface_whitelist;
  /// A writer that stays silent longer than this is considered dead by its readers.
  int64_t liveliness_lease_ns = 250'000'000;
  /// A participant silent longer than this is removed from discovery.
  int64_t participant_lease_ns = 3'000'000'000;
  /// Deadline of the 1 kHz streams: a reader notices when no sample came within it.
  int64_t stream_deadline_ns = 5'000'000;
  /// Network impairment of this participant's outgoing traffic (off when no links).
  impairment::ImpairmentConfig impairment;
};

/// Reads the `transport:` section. Throws ConfigError naming file and key.
ParticipantConfig parse_participant_config(const ConfigNode& section, const std::string& default_name);

}  // namespace teleop::transport
