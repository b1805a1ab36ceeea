// Leader, follower and twin on three "hosts" (network namespaces on a bridge), once per
// discovery setup: multicast, static unicast peers on a network that forbids multicast, and
// discovery servers (a primary and a backup). Each run checks that the nodes match within a
// stated time, that samples flow at rate, and that a cut link is noticed through liveliness
// and recovered from when the link comes back.
#include <gtest/gtest.h>

#include <csignal>
#include <iostream>

#include "netns_network.h"
#include "netns_nodes.h"

namespace teleop::test {
namespace {

constexpr int kLeaderHost = 0;
constexpr int kFollowerHost = 1;
constexpr int kTwinHost = 2;
constexpr int kServerHost = 3;        // the primary discovery server
constexpr int kBackupServerHost = kTwinHost;  // a client on its server's host

// the follower's link is down from kCutAt for kCutFor, longer than the
// participant lease (3 s), so the participants are dropped and must be discovered again
constexpr double kRunS = 14;  // from the leader's start to the stop
constexpr auto kCutAt = std::chrono::seconds(4);
constexpr auto kCutFor = std::chrono::seconds(4);
// stated bound: the first command reaches the follower within 5 s of the leader's start
constexpr uint64_t kMatchWithinCommands = 5000;

class DiscoveryNetns : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string reason = netns_unavailable_reason();
    // never a silent pass or skip: without namespaces this test fails and says why
    ASSERT_TRUE(reason.empty()) << reason;
    network_ = std::make_unique<NetnsNetwork>(4);
    nodes_ = std::make_unique<NetnsNodes>(*network_);
  }

  YAML::Node base_transport(int host) const {
    YAML::Node t;
    t["domain_id"] = 0;  // overridden per run by --domain
    t["udpv4"] = true;
    t["interface_whitelist"].push_back(network_->address(host));
    return t;
  }

  // The sanitizer build runs the follower's simulated arm at about half real time, so the leader's
  // scripted motion reaches it at about twice its speed and can trip the joint-velocity reflex
  // (seen once under ASan: 1.44x the threshold, safe hold to the end). The reflex is ReflexProcess's
  // subject; here it is off in that build only, so that the test's subject (discovery, flow,
  // recovery) is what decides. On a real arm the plant keeps real time whatever the controller does.
  static ConfigEdit follower_edit() {
#ifdef TELEOP_SANITIZED
    return [](YAML::Node& root) { root["follower"]["reflex"] = "off"; };
#else
    return {};
#endif
  }

  // starts follower and twin, then the leader; cuts and restores the follower's link; stops all
  // three together (so that none sees the others leave) and checks they exit cleanly
  void run_scenario(const std::function<YAML::Node(int host)>& transport) {
    // --duration only as a backstop: the test stops the nodes
    const double backstop_s = kRunS + 20;
    nodes_->start("follower", kFollowerHost, transport(kFollowerHost), backstop_s, follower_edit());
    nodes_->start("twin", kTwinHost, transport(kTwinHost), backstop_s);
    ASSERT_TRUE(nodes_->process("follower").wait_for_output("starting", std::chrono::seconds(20))) << nodes_->outputs();
    ASSERT_TRUE(nodes_->process("twin").wait_for_output("starting", std::chrono::seconds(20))) << nodes_->outputs();
    nodes_->start("leader", kLeaderHost, transport(kLeaderHost), backstop_s);
    nodes_->run_for(kCutAt);
    network_->set_link_up(kFollowerHost, false);
    nodes_->run_for(kCutFor);
    network_->set_link_up(kFollowerHost, true);
    nodes_->run_for(std::chrono::seconds(static_cast<int>(kRunS)) - kCutAt - kCutFor);
    for (const char* node : {"leader", "follower", "twin"}) nodes_->process(node).process().signal(SIGTERM);
    for (const char* node : {"leader", "follower", "twin"}) {
      ASSERT_EQ(nodes_->wait_exit(node, std::chrono::seconds(20)), 0) << node << " failed\n" << nodes_->outputs();
    }
  }

  void TearDown() override {
    if (!HasFailure() || !nodes_) return;
    for (const char* node : {"leader", "follower", "twin"}) {
      std::cerr << "---- report of " << node << " ----\n" << read_file(nodes_->report_path(node));
    }
  }

  void expect_matched_flowing_cut_and_recovered() {
    const auto leader = nodes_->report("leader");
    const auto follower = nodes_->report("follower");
    const auto twin = nodes_->report("twin");
    const auto& commands = received(follower, "teleop/leader/joint_command");
    const auto& states = received(leader, "teleop/follower/joint_state");
    const auto& device = received(twin, "teleop/leader/joint_state");

    // matched within the stated time: the leader numbers its commands from 1 at 1 kHz
    EXPECT_GE(commands.first_seq, 1u);
    EXPECT_LE(commands.first_seq, kMatchWithinCommands) << "first command arrived after more than 5 s";
    EXPECT_LE(device.first_seq, kMatchWithinCommands) << "the twin matched the leader after more than 5 s";

    // samples flowing at rate: outside the cut, at least half of what 1 kHz delivers (a third in
    // the sanitizer build, whose loops run at about half rate: 2285 of 5000 seen)
#ifdef TELEOP_SANITIZED
    constexpr double kShare = 0.35;
#else
    constexpr double kShare = 0.5;
#endif
    const double outside_cut_s = kRunS - std::chrono::duration<double>(kCutFor).count() - 5.0;
    const auto at_rate = static_cast<uint64_t>(kShare * 1000 * outside_cut_s);
    EXPECT_GE(commands.received, at_rate);
    EXPECT_GE(states.received, at_rate);
    EXPECT_GE(device.received, static_cast<uint64_t>(kShare * 1000 * (kRunS - 5.0))) << "the twin's link was never cut";

    // the cut is seen through liveliness on both sides of it, and drives the safe states
    EXPECT_GE(states.liveliness_lost, 1u) << "leader did not notice the follower's writer go silent";
    EXPECT_GE(commands.liveliness_lost, 1u) << "follower did not notice the leader's writer go silent";
    EXPECT_GE(counter(leader, "peer_lost_events"), 1.0);
    EXPECT_GE(counter(follower, "watchdog_trips"), 1.0);
    // a gap as long as the cut, then samples again
    EXPECT_GE(commands.lost, 1000u) << "no gap in the commands: was the link really cut?";
    // (half the nominal rate: a loaded sanitizer build ran 11266 cycles in 14 s)
    EXPECT_GT(commands.last_seq, static_cast<uint64_t>(0.5 * 1000 * (kRunS - 2))) << "commands did not come back";

    // recovered: both ended running, not holding
    EXPECT_EQ(leader.final_state, "running");
    EXPECT_EQ(follower.final_state, "running");
    EXPECT_EQ(twin.final_state, "running");
  }

  std::unique_ptr<NetnsNetwork> network_;
  std::unique_ptr<NetnsNodes> nodes_;
};

TEST_F(DiscoveryNetns, MulticastMatchesFlowsAndRecoversFromACutLink) {
  run_scenario([&](int host) {
    YAML::Node t = base_transport(host);
    t["discovery"]["mode"] = "multicast";
    return t;
  });
  expect_matched_flowing_cut_and_recovered();
}

TEST_F(DiscoveryNetns, InitialPeersWorkWhereTheNetworkForbidsMulticast) {
  network_->block_multicast();
  run_scenario([&](int host) {
    YAML::Node t = base_transport(host);
    t["discovery"]["mode"] = "peers";
    for (int h : {kLeaderHost, kFollowerHost, kTwinHost}) {
      if (h != host) t["initial_peers"].push_back(network_->address(h));
    }
    return t;
  });
  expect_matched_flowing_cut_and_recovered();
}

// the control for the test above: with multicast blocked, multicast discovery finds nobody
TEST_F(DiscoveryNetns, MulticastFindsNobodyWhereTheNetworkForbidsIt) {
  network_->block_multicast();
  const auto transport = [&](int host) {
    YAML::Node t = base_transport(host);
    t["discovery"]["mode"] = "multicast";
    return t;
  };
  nodes_->start("follower", kFollowerHost, transport(kFollowerHost), 5);
  nodes_->start("leader", kLeaderHost, transport(kLeaderHost), 5);
  ASSERT_EQ(nodes_->wait_exit("follower", std::chrono::seconds(30)), 0) << nodes_->outputs();
  ASSERT_EQ(nodes_->wait_exit("leader", std::chrono::seconds(30)), 0) << nodes_->outputs();
  EXPECT_EQ(received(nodes_->report("follower"), "teleop/leader/joint_command").received, 0u);
  EXPECT_EQ(received(nodes_->report("leader"), "teleop/follower/joint_state").received, 0u);
}

// two discovery servers (`fastdds discovery` runs fast-discovery-server; started directly so that
// a kill reaches the server itself); the primary is killed before the leader starts, so the
// leader's discovery and everyone's rediscovery after the cut go through the backup alone
TEST_F(DiscoveryNetns, DiscoveryServerWithBackupMatchesFlowsAndRecovers) {
  network_->block_multicast();
  const std::string primary = network_->address(kServerHost);
  const std::string backup = network_->address(kBackupServerHost);
  const std::string server = system_tool("fast-discovery-server");
  nodes_->start_program("server0", kServerHost, {server, "-i", "0", "-l", primary, "-p", "11811"});
  nodes_->start_program("server1", kBackupServerHost, {server, "-i", "1", "-l", backup, "-p", "11811"});
  ASSERT_TRUE(nodes_->process("server0").wait_for_output("Server is running", std::chrono::seconds(10)))
      << nodes_->outputs();
  ASSERT_TRUE(nodes_->process("server1").wait_for_output("Server is running", std::chrono::seconds(10)))
      << nodes_->outputs();
  run_scenario([&](int host) {
    YAML::Node t = base_transport(host);
    t["discovery"]["mode"] = "server";
    YAML::Node s0;
    s0["id"] = 0;
    s0["address"] = primary;
    YAML::Node s1;
    s1["id"] = 1;
    s1["address"] = backup;
    t["discovery"]["servers"].push_back(s0);
    t["discovery"]["servers"].push_back(s1);
    if (host == kLeaderHost) nodes_->process("server0").process().signal(SIGKILL);
    return t;
  });
  expect_matched_flowing_cut_and_recovered();
}

}  // namespace
}  // namespace teleop::test
