#pragma once
// How a node joins the DDS domain: domain, transports, peers, leases.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "teleop/common/config.h"
#include "teleop/transport/impairment/impairment_config.h"
#include "teleop/transport/naming.h"

namespace teleop::transport {

/// How participants find each other.
enum class DiscoveryMode {
  /// SPDP announcements to the domain's multicast group: one LAN, multicast allowed.
  kMulticast,
  /// Announcements to the listed `initial_peers` only (unicast): no multicast needed.
  kPeers,
  /// Client of Fast DDS discovery servers (`fastdds discovery`): no multicast, no peer lists.
  kServer,
};

/// A Fast DDS discovery server this participant is a client of.
struct DiscoveryServer {
  /// The server's id (`fastdds discovery -i ID`): it fixes the server's GUID prefix.
  int id = 0;
  std::string address;
  uint16_t port = 11811;
};

/// DDS Security (PKI-DH authentication, Access-Permissions, AES-GCM-GMAC): files in PEM / S/MIME.
struct SecurityConfig {
  std::string identity_ca;
  std::string identity_certificate;
  std::string private_key;
  std::string permissions_ca;
  std::string governance;
  std::string permissions;
  bool enabled() const { return !identity_certificate.empty(); }
};

/// The DDS domain of every shipped node config, and so of every node and tool not told otherwise:
/// the tools a newcomer starts meet the demo he just started. ROS 2's default domain 0 is left to
/// ROS 2 (a teleop node on 0 would see a whole ROS 2 system's discovery).
inline constexpr int kTeleopDomainId = 42;

struct ParticipantConfig {
  int domain_id = kTeleopDomainId;
  /// Participant name shown in discovery tools.
  std::string name = "teleop";
  /// A node's participant: another participant of the same name on the domain (two setups on one
  /// domain, a node started twice) is warned about when it appears.
  bool warn_same_name = false;
  /// After another participant appears, this participant's endpoints are announced again every
  /// `discovery_boost_period_ns` for `discovery_boost_ns` (0: never): a lost endpoint announcement
  /// is otherwise repaired only on Fast DDS's one-second heartbeat (discovery_booster.h).
  int64_t discovery_boost_ns = 2'000'000'000;
  int64_t discovery_boost_period_ns = 100'000'000;
  /// Network transport; needed for anything that leaves this host.
  bool udpv4 = true;
  /// Shared-memory transport between processes on one host: lower latency, but Fast DDS 2.9
  /// allocates three times per sent sample in it (measured), so it is off by default.
  bool shm = false;
  /// Unicast discovery peers, "address" or "address:port" (port 0 / absent: the domain's
  /// well-known discovery ports). Lets nodes find each other where multicast is not allowed.
  std::vector<std::string> initial_peers;
  DiscoveryMode discovery = DiscoveryMode::kMulticast;
  /// Discovery servers in order of preference (mode kServer): the first is the primary, the
  /// others back it up; the participant stays connected to all of them.
  std::vector<DiscoveryServer> discovery_servers;
  /// Network interfaces (IPv4 addresses) UDP may use, loopback always added; empty = all.
  std::vector<std::string> interface_whitelist;
  /// The Fast DDS XML profiles file the QoS comes from (qos_profiles.h); empty: the
  /// FASTRTPS_DEFAULT_PROFILES_FILE if it defines the teleop profiles, else the built-in
  /// config/qos/teleop_profiles.xml.
  std::string qos_profiles;
  /// The three below override the QoS profiles' values where set (unset: the profiles decide).
  /// A writer that stays silent longer than this is considered dead by its readers (every preset).
  std::optional<int64_t> liveliness_lease_ns;
  /// A participant silent longer than this is removed from discovery.
  std::optional<int64_t> participant_lease_ns;
  /// Deadline of the 1 kHz streams: a reader notices when no sample came within it.
  std::optional<int64_t> stream_deadline_ns;
  /// DDS names of topics and types: teleop's own, or ROS 2's (naming.h).
  Naming naming = Naming::kPlain;
  /// Authentication, access control and encryption; off when no files are given.
  SecurityConfig security;
  /// Network impairment of this participant's outgoing traffic (off when no links).
  impairment::ImpairmentConfig impairment;
};

/// Reads the `transport:` section. Throws ConfigError naming file and key.
ParticipantConfig parse_participant_config(const ConfigNode& section, const std::string& default_name);

/// How a tool (`teleop topic`, `monitor`, `record`, `reset`, ...) joins the nodes' bus: the
/// transport section of the node config at `node_config_path` (domain, discovery, peers,
/// security) when one is given, the defaults otherwise, without the node's impairment; `domain`
/// overrides. Throws ConfigError naming file and key.
ParticipantConfig tool_participant_config(const std::string& node_config_path, std::optional<int> domain,
                                          const std::string& name);

/// Name of a discovery mode as written in YAML.
const char* discovery_mode_name(DiscoveryMode mode);

}  // namespace teleop::transport
