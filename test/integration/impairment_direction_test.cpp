// Each direction of a link is configured on its own: the leader impairs only what it sends to
// the follower; what the follower sends back is untouched.
#include <gtest/gtest.h>

#include <csignal>

#include "process_helpers.h"
#include "teleop/runtime/node_report.h"

namespace teleop::test {
namespace {

const runtime::ReceivedTopic& received(const runtime::NodeReport& r, const std::string& topic) {
  for (const auto& t : r.received) {
    if (t.topic == topic) return t;
  }
  throw std::runtime_error("no topic " + topic);
}

TEST(ImpairmentDirection, LeaderToFollowerDelayedFollowerToLeaderNot) {
  const std::string dir = make_temp_dir();
  const std::string domain = std::to_string(unique_domain());
  auto args = [&](const std::string& node, std::vector<std::string> extra) {
    std::vector<std::string> a = {bin("teleop_" + node), "--config", source("config/nodes/" + node + ".yaml"),
                                  "--domain", domain, "--report", dir + "/" + node + ".yaml"};
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
  };
  RunningProcess follower(args("follower", {}));
  RunningProcess leader(args("leader", {"--impair", "follower=wan-35ms", "--seed", "5"}));
  ASSERT_TRUE(leader.wait_for_output("link to follower: profile wan-35ms", std::chrono::seconds(20))) << leader.output();
  leader.run_for(std::chrono::milliseconds(3000));
  ASSERT_EQ(leader.stop(SIGTERM, std::chrono::seconds(10)), 0) << leader.output();
  ASSERT_EQ(follower.stop(SIGTERM, std::chrono::seconds(10)), 0) << follower.output();

  const auto f = runtime::read_report(dir + "/follower.yaml");
  const auto l = runtime::read_report(dir + "/leader.yaml");
  const auto& command = received(f, "teleop/leader/joint_command");
  const auto& state = received(l, "teleop/follower/joint_state");
  ASSERT_GT(command.received, 1000u);
  ASSERT_GT(state.received, 1000u);
  // 17.5 ms one way on the impaired direction (histogram buckets are within 3 %; a loaded machine
  // wakes the releasing thread up to about a millisecond late: 18.35 ms seen under a parallel run)
  EXPECT_NEAR(command.latency_p50_ns * 1e-6, 17.5, 0.03 * 17.5 + 1.0);
  EXPECT_LT(state.latency_p50_ns * 1e-6, 5.0) << "the other direction is not impaired";
  ASSERT_EQ(l.links.size(), 1u);
  EXPECT_EQ(l.links[0].to, "follower");
  EXPECT_EQ(l.impairment_seed, 5u);
  EXPECT_GT(l.links[0].messages, 1000u) << "discovery mapped the follower's locators to its link";
  EXPECT_TRUE(f.links.empty());
}

}  // namespace
}  // namespace teleop::test
