#include "teleop/transport/participant_config.h"

#include <arpa/inet.h>

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

}  // namespace

ParticipantConfig parse_participant_config(const ConfigNode& section, const std::string& default_name) {
  ParticipantConfig c;
  c.domain_id = static_cast<int>(section.get_int("domain_id", Range{0, 232}));
  c.name = section.get_string("participant_name", default_name);
  c.udpv4 = section.get_bool("udpv4", true);
  c.shm = section.get_bool("shm", false);
  if (!c.udpv4 && !c.shm) throw section.error("shm", "at least one of udpv4 and shm must be true");
  c.initial_peers = section.get_string_list("initial_peers");
  for (const auto& peer : c.initial_peers) validate_peer(section, peer);
  c.interface_whitelist = section.get_string_list("interface_whitelist");
  for (const auto& itf : c.interface_whitelist) {
    if (!is_ipv4(itf)) throw section.error("interface_whitelist", "'" + itf + "' is not an IPv4 address");
  }
  c.liveliness_lease_ns = section.get_int("liveliness_lease_ms", kLeaseMs, 250) * 1'000'000;
  c.participant_lease_ns = section.get_int("participant_lease_ms", kLeaseMs, 3000) * 1'000'000;
  if (c.participant_lease_ns < c.liveliness_lease_ns) {
    throw section.error("participant_lease_ms", "must not be shorter than liveliness_lease_ms");
  }
  c.stream_deadline_ns =
      static_cast<int64_t>(section.get_double("stream_deadline_ms", Range{0.1, 60'000}, 5.0) * 1e6);
  if (auto imp = section.optional_child("impairment")) c.impairment = impairment::parse_impairment_config(*imp);
  return c;
}

}  // namespace teleop::transport
