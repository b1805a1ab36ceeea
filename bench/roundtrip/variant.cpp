// The variants a run measures, by name, and the DDS participant each side of a DDS variant uses.

#include "roundtrip.h"

namespace teleop::bench {
namespace {

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

}  // namespace

const char* name_of(Variant v) {
  switch (v) {
    case Variant::kDdsUdp:
      return "dds-udp";
    case Variant::kDdsShm:
      return "dds-shm";
    case Variant::kDdsSecure:
      return "dds-sec";
    case Variant::kRawUdp:
      return "raw-udp";
  }
  return "?";
}

std::optional<Variant> parse_variant(const std::string& name) {
  for (Variant v : {Variant::kDdsUdp, Variant::kDdsShm, Variant::kDdsSecure, Variant::kRawUdp}) {
    if (name == name_of(v)) return v;
  }
  return std::nullopt;
}

transport::ParticipantConfig dds_config(Variant v, int domain, const std::string& name, const std::string& pki,
                                        const std::string& identity) {
  transport::ParticipantConfig config;
  config.domain_id = domain;
  config.name = name;
  // one transport only, so that the variant measures exactly that transport (discovery included)
  config.udpv4 = v == Variant::kDdsUdp || v == Variant::kDdsSecure;
  config.shm = v == Variant::kDdsShm;
  if (v == Variant::kDdsSecure) config.security = bench_security(pki, identity);
  return config;
}

}  // namespace teleop::bench
