#include "teleop/transport/participant_config.h"

#include <arpa/inet.h>

#include <iterator>

namespace teleop::transport {
namespace {

constexpr Range kLeaseMs{1, 3'600'000};

bool is_ipv4(const std::string& text) {
  in_addr addr{};
  return inet_pton(AF_INET, text.c_str(), &addr) == 1;
}

// "a.b.c.d" or "a.b.c.d:port"
void validate_peer(const ConfigNode& section, const std::string& peer) {
  const auto colon = peer.rfind(':');
  const std::string host = peer.substr(0, colon);
  if (!is_ipv4(host)) {
    throw section.error("initial_peers", "'" + peer + "' is not an IPv4 address (optionally with :port)");
  }
  if (colon != std::string::npos) {
    const std::string port = peer.substr(colon + 1);
    const bool numeric = !port.empty() && port.find_first_not_of("0123456789") == std::string::npos;
    if (!numeric || port.size() > 5 || std::stoi(port) > 65535) {
      throw section.error("initial_peers", "'" + peer + "' has an invalid port");
    }
  }
}

constexpr const char* kModeNames[] = {"multicast", "peers", "server"};

DiscoveryServer parse_discovery_server(const ConfigNode& entry) {
  DiscoveryServer server;
  server.id = static_cast<int>(entry.get_int("id", Range{0, 255}));
  server.address = entry.get_string("address");
  if (!is_ipv4(server.address)) throw entry.error("address", "'" + server.address + "' is not an IPv4 address");
  server.port = static_cast<uint16_t>(entry.get_int("port", Range{1, 65535}, server.port));
  return server;
}

DiscoveryMode parse_mode(const ConfigNode& discovery) {
  const std::string mode = discovery.get_choice("mode", {std::begin(kModeNames), std::end(kModeNames)});
  int index = 0;
  while (mode != kModeNames[index]) ++index;
  return static_cast<DiscoveryMode>(index);
}

std::vector<DiscoveryServer> parse_servers(const ConfigNode& discovery) {
  std::vector<DiscoveryServer> servers;
  for (const auto& entry : discovery.get_node_list("servers")) {
    const DiscoveryServer server = parse_discovery_server(entry);
    for (const auto& earlier : servers) {
      if (earlier.id == server.id)
        throw entry.error("id", "server id " + std::to_string(server.id) + " is listed twice");
    }
    servers.push_back(server);
  }
  return servers;
}

// each mode uses its own list and no other
void check_discovery(const ConfigNode& section, const ConfigNode& discovery, const ParticipantConfig& c) {
  const bool server = c.discovery == DiscoveryMode::kServer;
  const bool peers = c.discovery == DiscoveryMode::kPeers;
  if (server && c.discovery_servers.empty()) {
    throw discovery.error("servers", "mode server needs at least one server ({id, address, port})");
  }
  if (!server && !c.discovery_servers.empty()) {
    throw discovery.error(
        "servers", std::string("servers are only used with mode server, not ") + discovery_mode_name(c.discovery));
  }
  if (peers && c.initial_peers.empty()) {
    throw discovery.error("mode", "mode peers needs transport.initial_peers (the hosts to announce to)");
  }
  if (!peers && !c.initial_peers.empty()) {
    throw section.error("initial_peers", "initial peers replace multicast and servers: set discovery.mode: peers");
  }
}

// `discovery:` (optional): without it, listed initial peers mean unicast discovery to them
void parse_discovery(const ConfigNode& section, ParticipantConfig& c) {
  const auto discovery = section.optional_child("discovery");
  if (!discovery) {
    c.discovery = c.initial_peers.empty() ? DiscoveryMode::kMulticast : DiscoveryMode::kPeers;
    return;
  }
  c.discovery = parse_mode(*discovery);
  c.discovery_servers = parse_servers(*discovery);
  check_discovery(section, *discovery, c);
}

// `security:` (optional): every file must exist; their contents are checked when the participant starts
SecurityConfig parse_security(const ConfigNode& section) {
  const auto security = section.optional_child("security");
  if (!security) return {};
  SecurityConfig s;
  s.identity_ca = security->get_path("identity_ca");
  s.identity_certificate = security->get_path("identity_certificate");
  s.private_key = security->get_path("private_key");
  s.permissions_ca = security->get_path("permissions_ca");
  s.governance = security->get_path("governance");
  s.permissions = security->get_path("permissions");
  return s;
}

// the QoS profiles file and the keys that override it; where both leases are given here they are
// checked here, else against the profiles' values when the participant resolves them
void parse_qos(const ConfigNode& section, ParticipantConfig& c) {
  if (section.has("qos_profiles")) c.qos_profiles = section.get_path("qos_profiles");
  if (section.has("liveliness_lease_ms")) {
    c.liveliness_lease_ns = section.get_int("liveliness_lease_ms", kLeaseMs) * 1'000'000;
  }
  if (section.has("participant_lease_ms")) {
    c.participant_lease_ns = section.get_int("participant_lease_ms", kLeaseMs) * 1'000'000;
  }
  if (c.participant_lease_ns && c.liveliness_lease_ns && *c.participant_lease_ns < *c.liveliness_lease_ns) {
    throw section.error("participant_lease_ms", "must not be shorter than liveliness_lease_ms");
  }
  if (section.has("stream_deadline_ms")) {
    c.stream_deadline_ns = static_cast<int64_t>(section.get_double("stream_deadline_ms", Range{0.1, 60'000}) * 1e6);
  }
  const std::string naming = section.get_choice("naming", {"plain", "ros2"}, "plain");
  c.naming = naming == "ros2" ? Naming::kRos2 : Naming::kPlain;
  // re-announcing the endpoints after a peer appears (0: never); every 100 ms meanwhile
  c.discovery_boost_ns = section.get_int("discovery_boost_ms", Range{0, 60'000}, c.discovery_boost_ns / 1'000'000) * 1'000'000;
}

}  // namespace

const char* discovery_mode_name(DiscoveryMode mode) { return kModeNames[static_cast<int>(mode)]; }

ParticipantConfig parse_participant_config(const ConfigNode& section, const std::string& default_name) {
  ParticipantConfig c;
  c.domain_id = static_cast<int>(section.get_int("domain_id", Range{0, 232}));
  c.name = section.get_string("participant_name", default_name);
  c.udpv4 = section.get_bool("udpv4", true);
  c.shm = section.get_bool("shm", false);
  if (!c.udpv4 && !c.shm) throw section.error("shm", "at least one of udpv4 and shm must be true");
  c.initial_peers = section.get_string_list("initial_peers");
  for (const auto& peer : c.initial_peers) validate_peer(section, peer);
  parse_discovery(section, c);
  c.interface_whitelist = section.get_string_list("interface_whitelist");
  for (const auto& itf : c.interface_whitelist) {
    if (!is_ipv4(itf)) throw section.error("interface_whitelist", "'" + itf + "' is not an IPv4 address");
  }
  parse_qos(section, c);
  c.security = parse_security(section);
  if (auto imp = section.optional_child("impairment")) c.impairment = impairment::parse_impairment_config(*imp);
  return c;
}

ParticipantConfig tool_participant_config(const std::string& node_config_path, std::optional<int> domain,
                                          const std::string& name) {
  ParticipantConfig config;
  if (!node_config_path.empty()) {
    // the node's own transport section, so the tool meets the nodes where they are
    const ConfigNode root = ConfigNode::load_file(node_config_path);
    config = parse_participant_config(root.child("transport"), name);
  }
  config.name = name;
  config.impairment = {};  // a tool observes the network; it does not add to it
  if (domain) config.domain_id = *domain;
  return config;
}

}  // namespace teleop::transport
