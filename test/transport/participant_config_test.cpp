#include "teleop/transport/participant_config.h"

#include <gtest/gtest.h>

#include "test_helpers.h"

#include <string>
#include <utility>
#include <vector>

namespace teleop::transport {
namespace {

ParticipantConfig parse(const std::string& text) {
  const ConfigNode root = ConfigNode::load_string(text, "node.yaml");
  ParticipantConfig c = parse_participant_config(root.child("transport"), "leader");
  root.check_all_used();
  return c;
}

std::string error_of(const std::string& text) {
  try {
    parse(text);
  } catch (const ConfigError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no ConfigError for:\n" << text;
  return {};
}

TEST(ParseParticipantConfig, AppliesDefaultsWhenOnlyDomainGiven) {
  const ParticipantConfig c = parse("transport:\n  domain_id: 7\n");
  const ParticipantConfig defaults;
  EXPECT_EQ(c.domain_id, 7);
  EXPECT_EQ(c.name, "leader");  // the default name passed in
  EXPECT_TRUE(c.udpv4);
  EXPECT_FALSE(c.shm);  // opt-in: Fast DDS 2.9 allocates per sample in it
  EXPECT_TRUE(c.initial_peers.empty());
  EXPECT_TRUE(c.interface_whitelist.empty());
  // unset: the QoS profiles decide
  EXPECT_FALSE(c.liveliness_lease_ns.has_value());
  EXPECT_FALSE(c.participant_lease_ns.has_value());
  EXPECT_FALSE(c.stream_deadline_ns.has_value());
  EXPECT_EQ(c.qos_profiles, "");
  EXPECT_EQ(c.naming, Naming::kPlain);
}

TEST(ParseParticipantConfig, ReadsEveryKeyWhenAllGiven) {
  const ParticipantConfig c = parse(
      "transport:\n"
      "  domain_id: 232\n"
      "  participant_name: robot_a\n"
      "  udpv4: true\n"
      "  shm: false\n"
      "  initial_peers: [192.168.1.10, \"10.0.0.2:7412\", \"127.0.0.1:0\"]\n"
      "  interface_whitelist: [127.0.0.1]\n"
      "  liveliness_lease_ms: 100\n"
      "  participant_lease_ms: 2000\n"
      "  stream_deadline_ms: 2.5\n");
  EXPECT_EQ(c.domain_id, 232);
  EXPECT_EQ(c.name, "robot_a");
  EXPECT_TRUE(c.udpv4);
  EXPECT_FALSE(c.shm);
  EXPECT_EQ(c.initial_peers, (std::vector<std::string>{"192.168.1.10", "10.0.0.2:7412", "127.0.0.1:0"}));
  EXPECT_EQ(c.interface_whitelist, (std::vector<std::string>{"127.0.0.1"}));
  EXPECT_EQ(c.liveliness_lease_ns, 100'000'000);
  EXPECT_EQ(c.participant_lease_ns, 2'000'000'000);
  EXPECT_EQ(c.stream_deadline_ns, 2'500'000);
}

TEST(ParseParticipantConfig, AcceptsEqualLeases) {
  const ParticipantConfig c =
      parse("transport:\n  domain_id: 0\n  liveliness_lease_ms: 500\n  participant_lease_ms: 500\n");
  EXPECT_EQ(c.participant_lease_ns, c.liveliness_lease_ns);
}

TEST(ParseParticipantConfig, AcceptsShmOnlyWhenUdpOff) {
  const ParticipantConfig c = parse("transport:\n  domain_id: 0\n  udpv4: false\n  shm: true\n");
  EXPECT_FALSE(c.udpv4);
  EXPECT_TRUE(c.shm);
}

TEST(ParseParticipantConfig, RequiresDomainId) {
  EXPECT_EQ(error_of("transport:\n  shm: true\n"), "node.yaml:2: transport.domain_id: missing required key");
}

TEST(ParseParticipantConfig, RejectsDomainIdOutOfRange) {
  EXPECT_EQ(error_of("transport:\n  domain_id: 233\n"),
            "node.yaml:2: transport.domain_id: value 233 is out of range [0, 232]");
  EXPECT_EQ(error_of("transport:\n  domain_id: -1\n"),
            "node.yaml:2: transport.domain_id: value -1 is out of range [0, 232]");
}

TEST(ParseParticipantConfig, RejectsBadIpv4Peer) {
  EXPECT_EQ(error_of("transport:\n  domain_id: 0\n  initial_peers: [192.168.1.300]\n"),
            "node.yaml:3: transport.initial_peers: '192.168.1.300' is not an IPv4 address (optionally with :port)");
  EXPECT_EQ(error_of("transport:\n  domain_id: 0\n  initial_peers: [robot.local]\n"),
            "node.yaml:3: transport.initial_peers: 'robot.local' is not an IPv4 address (optionally with :port)");
  EXPECT_EQ(error_of("transport:\n  domain_id: 0\n  initial_peers: [\"fe80::1\"]\n"),
            "node.yaml:3: transport.initial_peers: 'fe80::1' is not an IPv4 address (optionally with :port)");
  EXPECT_EQ(error_of("transport:\n  domain_id: 0\n  initial_peers: [\":7400\"]\n"),
            "node.yaml:3: transport.initial_peers: ':7400' is not an IPv4 address (optionally with :port)");
}

TEST(ParseParticipantConfig, RejectsBadPeerPort) {
  for (const std::string peer : {"10.0.0.1:", "10.0.0.1:65536", "10.0.0.1:99999999999", "10.0.0.1:74a0", "10.0.0.1:-1"}) {
    EXPECT_EQ(error_of("transport:\n  domain_id: 0\n  initial_peers: [\"" + peer + "\"]\n"),
              "node.yaml:3: transport.initial_peers: '" + peer + "' has an invalid port")
        << peer;
  }
}

TEST(ParseParticipantConfig, AcceptsHighestPeerPort) {
  const ParticipantConfig c = parse("transport:\n  domain_id: 0\n  initial_peers: [\"10.0.0.1:65535\"]\n");
  EXPECT_EQ(c.initial_peers.at(0), "10.0.0.1:65535");
}

TEST(ParseParticipantConfig, RejectsBadInterfaceAddress) {
  EXPECT_EQ(error_of("transport:\n  domain_id: 0\n  interface_whitelist: [eth0]\n"),
            "node.yaml:3: transport.interface_whitelist: 'eth0' is not an IPv4 address");
}

TEST(ParseParticipantConfig, RejectsBothTransportsOff) {
  EXPECT_EQ(error_of("transport:\n  domain_id: 0\n  udpv4: false\n  shm: false\n"),
            "node.yaml:4: transport.shm: at least one of udpv4 and shm must be true");
  // shm is off by default, so turning UDP off alone leaves nothing
  EXPECT_EQ(error_of("transport:\n  domain_id: 0\n  udpv4: false\n"),
            "node.yaml:2: transport.shm: at least one of udpv4 and shm must be true");
}

TEST(ParseParticipantConfig, RejectsParticipantLeaseShorterThanLivelinessLease) {
  EXPECT_EQ(error_of("transport:\n  domain_id: 0\n  liveliness_lease_ms: 1000\n  participant_lease_ms: 999\n"),
            "node.yaml:4: transport.participant_lease_ms: must not be shorter than liveliness_lease_ms");
  // with one of them given here the other is the QoS profiles': the participant checks the pair
  // it resolves (qos_profiles_test: LivelinessLeaseLongerThanTheParticipantLeaseIsAConfigError)
  EXPECT_EQ(parse("transport:\n  domain_id: 0\n  liveliness_lease_ms: 5000\n").liveliness_lease_ns, 5'000'000'000);
}

TEST(ParseParticipantConfig, ReadsNaming) {
  EXPECT_EQ(parse("transport:\n  domain_id: 0\n  naming: ros2\n").naming, Naming::kRos2);
  EXPECT_EQ(parse("transport:\n  domain_id: 0\n  naming: plain\n").naming, Naming::kPlain);
  EXPECT_EQ(error_of("transport:\n  domain_id: 0\n  naming: ros\n"),
            "node.yaml:3: transport.naming: 'ros' is not one of: plain, ros2");
}

TEST(ParseParticipantConfig, ResolvesQosProfilesRelativeToTheConfigFile) {
  test::TempDir dir("teleop_participant_config");
  const std::string xml = dir.write("profiles.xml", "<dds/>\n");
  const std::string yaml = dir.write("node.yaml", "transport:\n  domain_id: 0\n  qos_profiles: profiles.xml\n");
  const ConfigNode root = ConfigNode::load_file(yaml);
  EXPECT_EQ(parse_participant_config(root.child("transport"), "leader").qos_profiles, xml);
  // a file that is not there is the YAML's error, before any participant exists
  const std::string missing = dir.write("missing.yaml", "transport:\n  domain_id: 0\n  qos_profiles: nope.xml\n");
  const std::string message = test::error_of<ConfigError>(
      [&] { parse_participant_config(ConfigNode::load_file(missing).child("transport"), "leader"); });
  EXPECT_NE(message.find("transport.qos_profiles"), std::string::npos) << message;
}

TEST(ParseParticipantConfig, RejectsLeasesAndDeadlineOutOfRange) {
  EXPECT_EQ(error_of("transport:\n  domain_id: 0\n  liveliness_lease_ms: 0\n"),
            "node.yaml:3: transport.liveliness_lease_ms: value 0 is out of range [1, 3.6e+06]");
  EXPECT_EQ(error_of("transport:\n  domain_id: 0\n  participant_lease_ms: 3600001\n"),
            "node.yaml:3: transport.participant_lease_ms: value 3600001 is out of range [1, 3.6e+06]");
  EXPECT_EQ(error_of("transport:\n  domain_id: 0\n  stream_deadline_ms: 0.05\n"),
            "node.yaml:3: transport.stream_deadline_ms: value 0.05 is out of range [0.1, 60000]");
  EXPECT_EQ(error_of("transport:\n  domain_id: 0\n  stream_deadline_ms: .nan\n"),
            "node.yaml:3: transport.stream_deadline_ms: value .nan is out of range [0.1, 60000]");
}

TEST(ParseParticipantConfig, RejectsWrongTypes) {
  EXPECT_EQ(error_of("transport:\n  domain_id: zero\n"),
            "node.yaml:2: transport.domain_id: expected an integer, got 'zero'");
  EXPECT_EQ(error_of("transport:\n  domain_id: 0\n  shm: yes please\n"),
            "node.yaml:3: transport.shm: expected true or false, got 'yes please'");
  EXPECT_EQ(error_of("transport:\n  domain_id: 0\n  initial_peers: 10.0.0.1\n"),
            "node.yaml:3: transport.initial_peers: expected a list of strings, got '10.0.0.1'");
}

TEST(ParseParticipantConfig, DiscoversByMulticastByDefaultAndByPeersWhenPeersListed) {
  EXPECT_EQ(parse("transport:\n  domain_id: 0\n").discovery, DiscoveryMode::kMulticast);
  // configs from before the discovery section: listed peers meant unicast discovery
  EXPECT_EQ(parse("transport:\n  domain_id: 0\n  initial_peers: [10.0.0.2]\n").discovery, DiscoveryMode::kPeers);
}

TEST(ParseParticipantConfig, ReadsDiscoveryServersInOrder) {
  const ParticipantConfig c = parse(
      "transport:\n"
      "  domain_id: 0\n"
      "  discovery:\n"
      "    mode: server\n"
      "    servers:\n"
      "      - {id: 0, address: 10.0.0.1}\n"
      "      - {id: 3, address: 10.0.0.2, port: 11900}\n");
  EXPECT_EQ(c.discovery, DiscoveryMode::kServer);
  ASSERT_EQ(c.discovery_servers.size(), 2u);
  EXPECT_EQ(c.discovery_servers[0].id, 0);
  EXPECT_EQ(c.discovery_servers[0].address, "10.0.0.1");
  EXPECT_EQ(c.discovery_servers[0].port, 11811);  // fastdds discovery's default port
  EXPECT_EQ(c.discovery_servers[1].id, 3);
  EXPECT_EQ(c.discovery_servers[1].port, 11900);
  EXPECT_STREQ(discovery_mode_name(c.discovery), "server");
}

// each case: the YAML after `head`, and the error it must give
void expect_errors(const std::string& head, const std::vector<std::pair<std::string, std::string>>& cases) {
  for (const auto& [yaml, error] : cases) EXPECT_EQ(error_of(head + yaml), error) << yaml;
}

TEST(ParseParticipantConfig, RejectsInconsistentDiscovery) {
  expect_errors(
      "transport:\n  domain_id: 0\n",
      {{"  discovery:\n    mode: server\n",
        "node.yaml:4: transport.discovery.servers: mode server needs at least one server ({id, address, port})"},
       {"  discovery:\n    mode: peers\n",
        "node.yaml:4: transport.discovery.mode: mode peers needs transport.initial_peers (the hosts to announce "
        "to)"},
       {"  initial_peers: [10.0.0.2]\n  discovery:\n    mode: multicast\n",
        "node.yaml:3: transport.initial_peers: initial peers replace multicast and servers: set "
        "discovery.mode: peers"},
       {"  discovery:\n    mode: multicast\n    servers: [{id: 0, address: 10.0.0.1}]\n",
        "node.yaml:5: transport.discovery.servers: servers are only used with mode server, not multicast"},
       {"  discovery:\n    mode: broadcast\n",
        "node.yaml:4: transport.discovery.mode: 'broadcast' is not one of: multicast, peers, server"}});
}

TEST(ParseParticipantConfig, RejectsBadDiscoveryServer) {
  expect_errors(
      "transport:\n  domain_id: 0\n  discovery:\n    mode: server\n    servers:\n",
      {{"      - {id: 0, address: server.lan}\n",
        "node.yaml:6: transport.discovery.servers[0].address: 'server.lan' is not an IPv4 address"},
       {"      - {id: 256, address: 10.0.0.1}\n",
        "node.yaml:6: transport.discovery.servers[0].id: value 256 is out of range [0, 255]"},
       {"      - {id: 1, address: 10.0.0.1}\n      - {id: 1, address: 10.0.0.2}\n",
        "node.yaml:7: transport.discovery.servers[1].id: server id 1 is listed twice"},
       {"      - {address: 10.0.0.1}\n", "node.yaml:6: transport.discovery.servers[0].id: missing required key"}});
}

TEST(ParseParticipantConfig, SecurityIsOffWithoutItsSection) {
  EXPECT_FALSE(parse("transport:\n  domain_id: 0\n").security.enabled());
}

TEST(ParseParticipantConfig, NamesTheMissingSecurityFile) {
  const std::string error = error_of("transport:\n  domain_id: 0\n  security:\n    identity_ca: /nonexistent/ca.pem\n");
  EXPECT_EQ(error, "node.yaml:4: transport.security.identity_ca: no file /nonexistent/ca.pem");
}

TEST(ParseParticipantConfig, RejectsUnknownKeyInSection) {
  EXPECT_EQ(error_of("transport:\n  domain_id: 0\n  multicast: true\n"), "node.yaml:3: transport.multicast: unknown key");
}

}  // namespace
}  // namespace teleop::transport
