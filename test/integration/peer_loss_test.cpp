// A peer dying (SIGKILL: no goodbye) drives the survivor into its defined safe state.
#include <gtest/gtest.h>

#include <csignal>

#include "process_helpers.h"
#include "report_counter.h"
#include "teleop/runtime/node_report.h"

namespace teleop::test {
namespace {

struct Pair {
  std::string dir = make_temp_dir();
  std::string domain = std::to_string(unique_domain());
  std::vector<std::string> args(const std::string& node) const {
    return {bin("teleop_" + node), "--config", source("config/nodes/" + node + ".yaml"), "--domain", domain,
            "--report", dir + "/" + node + ".yaml"};
  }
};

TEST(PeerLoss, LeaderFreezesAndReportsWhenTheFollowerDies) {
  Pair pair;
  RunningProcess follower(pair.args("follower"));
  RunningProcess leader(pair.args("leader"));
  ASSERT_TRUE(leader.wait_for_output("starting", std::chrono::seconds(20))) << leader.output();
  leader.run_for(std::chrono::milliseconds(1500));
  follower.process().signal(SIGKILL);
  leader.run_for(std::chrono::milliseconds(1000));
  ASSERT_EQ(leader.stop(SIGTERM, std::chrono::seconds(10)), 0) << leader.output();

  const auto report = runtime::read_report(pair.dir + "/leader.yaml");
  EXPECT_EQ(report.final_state, "safe_hold");
  EXPECT_GE(counter(report, "peer_lost_events"), 1.0);
}

}  // namespace
}  // namespace teleop::test
