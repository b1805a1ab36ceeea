// The variants a run measures, by name, and the DDS participant each side of a teleop variant
// uses.

#include <unistd.h>

#include <sstream>
#include <stdexcept>

#include "roundtrip.h"
#include "teleop/transport/topics.h"

namespace teleop::bench {
namespace {

constexpr Variant kAll[] = {Variant::kRawUdp, Variant::kBareDds,    Variant::kDdsUdp, Variant::kDdsImpaired,
                            Variant::kDdsShm, Variant::kDdsSecure, Variant::kDdsPerf};

// the secure variant's identities: the pinger is the leader (publishes leader/joint_state, reads
// follower/joint_state); the echo the reverse, which only the benchmark's own identity may do
transport::SecurityConfig bench_security(const std::string& pki, const std::string& identity) {
  transport::SecurityConfig s;
  s.identity_ca = pki + "/identity_ca.pem";
  s.identity_certificate = pki + "/" + identity + "/identity.pem";
  s.private_key = pki + "/" + identity + "/key.pem";
  s.permissions_ca = pki + "/permissions_ca.pem";
  s.governance = pki + "/governance.p7s";
  s.permissions = pki + "/" + identity + "/permissions.p7s";
  return s;
}

bool can_run(Variant v, const Options& opt) {
  if (v == Variant::kDdsSecure) return !opt.pki.empty();
  if (v == Variant::kDdsPerf) return ddsperf_available();
  return true;
}

}  // namespace

const char* name_of(Variant v) {
  switch (v) {
    case Variant::kRawUdp:
      return "raw-udp";
    case Variant::kBareDds:
      return "fastdds";
    case Variant::kDdsUdp:
      return "dds-udp";
    case Variant::kDdsImpaired:
      return "dds-imp";
    case Variant::kDdsShm:
      return "dds-shm";
    case Variant::kDdsSecure:
      return "dds-sec";
    case Variant::kDdsPerf:
      return "ddsperf";
  }
  return "?";
}

std::optional<Variant> parse_variant(const std::string& name) {
  for (Variant v : kAll) {
    if (name == name_of(v)) return v;
  }
  return std::nullopt;
}

bool is_teleop(Variant v) {
  return v == Variant::kDdsUdp || v == Variant::kDdsImpaired || v == Variant::kDdsShm || v == Variant::kDdsSecure;
}

std::vector<Variant> selected_variants(const Options& opt) {
  std::vector<Variant> variants;
  if (opt.variants == "all") {
    for (Variant v : kAll) {
      if (can_run(v, opt)) variants.push_back(v);
    }
    return variants;
  }
  std::istringstream names(opt.variants);
  std::string name;
  while (std::getline(names, name, ',')) {
    const auto v = parse_variant(name);
    if (!v) throw std::invalid_argument("unknown variant '" + name + "'");
    if (*v == Variant::kDdsSecure && opt.pki.empty()) throw std::invalid_argument("dds-sec needs --pki DIR");
    variants.push_back(*v);
  }
  return variants;
}

TopicNames topic_names(int topics) {
  TopicNames names;
  for (int i = 0; i < topics; ++i) {
    const std::string suffix = i == 0 ? "" : "_" + std::to_string(i);
    names.ping.push_back(transport::topics::kLeaderState.name + suffix);
    names.pong.push_back(transport::topics::kFollowerState.name + suffix);
  }
  return names;
}

transport::ParticipantConfig dds_config(Variant v, int domain, const std::string& name, const std::string& pki,
                                        const std::string& identity) {
  transport::ParticipantConfig config;
  config.domain_id = domain;
  config.name = name;
  // one transport only, so that the variant measures exactly that transport (discovery included)
  config.udpv4 = v != Variant::kDdsShm;
  config.shm = v == Variant::kDdsShm;
  if (v == Variant::kDdsSecure) config.security = bench_security(pki, identity);
  // the impairment layer in place, every message through it, but a profile that does nothing
  if (v == Variant::kDdsImpaired) config.impairment.links.push_back({transport::impairment::kAnyPeer, {}});
  return config;
}

}  // namespace teleop::bench
