// A two-arm leader station and a two-arm follower as real processes over DDS: each hand commands
// its own arm on its own topics (T/left, T/right), both follower arms in one shared simulation.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "process_helpers.h"
#include "teleop/experiment/trace.h"
#include "teleop/runtime/node_report.h"

namespace teleop::test {
namespace {

constexpr double kLeftHome[7] = {-0.066, 0.739, -0.020, -2.103, 0.044, 2.839, 0.0};
constexpr double kRightHome[7] = {0.066, 0.739, 0.020, -2.103, -0.044, 2.839, 0.0};

// home, with joint `joint` moved by `amplitude` smoothly over 1.5 s, then held to 4 s
std::string recording(const double (&home)[7], int joint, double amplitude) {
  std::string csv = "t_s,q_0,q_1,q_2,q_3,q_4,q_5,q_6\n";
  for (int k = 0; k <= 400; ++k) {
    const double t = 0.01 * k;
    const double s = std::min(1.0, t / 1.5);
    char line[256];
    double q[7];
    for (int j = 0; j < 7; ++j) q[j] = home[j];
    q[joint] += amplitude * s * s * (3 - 2 * s);
    std::snprintf(line, sizeof line, "%.3f,%.9f,%.9f,%.9f,%.9f,%.9f,%.9f,%.9f\n", t, q[0], q[1], q[2], q[3], q[4], q[5], q[6]);
    csv += line;
  }
  return csv;
}

double last(const std::vector<double>& column) { return column.back(); }

TEST(TwoArmProcesses, EachHandMovesOnlyItsOwnArm) {
  const std::string dir = make_temp_dir();
  const int domain = unique_domain();
  // wrist joints only: the hands turn in place, clear of the box between them
  write_file(dir + "/left.csv", recording(kLeftHome, 6, 0.4));
  write_file(dir + "/right.csv", recording(kRightHome, 4, 0.3));
  auto args = [&](const std::string& node, const std::string& config, const std::string& seconds) {
    return std::vector<std::string>{bin("teleop_" + node), "--config", source("config/nodes/" + config), "--domain",
                                    std::to_string(domain), "--report", dir + "/" + node + ".yaml", "--trace",
                                    dir + "/" + node + ".csv", "--duration", seconds};
  };
  // the operator stays 2 s longer than the robot: the follower ends still commanded (running), as
  // it would not if its longer start (two arms and a box in MuJoCo) let the leader end first
  auto leader_args = args("leader", "leader_box_task.yaml", "6");
  for (const std::string side : {"left", "right"}) {
    leader_args.insert(leader_args.end(), {"--set", "leader.arms." + side + ".recording=" + dir + "/" + side + ".csv"});
  }
  auto follower_args = args("follower", "follower_box_task.yaml", "4");
  // the box task's probe, as its experiment asks for it
  follower_args.insert(follower_args.end(), {"--set", "node.probes=[box_task]"});
  RunningProcess follower(follower_args);
  RunningProcess leader(leader_args);
  ASSERT_EQ(follower.stop(0, std::chrono::seconds(30)), 0) << follower.output();
  ASSERT_EQ(leader.stop(0, std::chrono::seconds(30)), 0) << leader.output();

  const auto trace = experiment::read_trace(dir + "/follower.csv");
  EXPECT_NEAR(last(trace.column("left_q_6")), kLeftHome[6] + 0.4, 0.03) << "the left hand turned the left wrist";
  EXPECT_NEAR(last(trace.column("left_q_4")), kLeftHome[4], 0.03) << "and not the joint the right hand moved";
  EXPECT_NEAR(last(trace.column("right_q_4")), kRightHome[4] + 0.3, 0.03);
  EXPECT_NEAR(last(trace.column("right_q_6")), kRightHome[6], 0.03);

  // the box task's columns (the box_task probe): the box stays in its socket, on its supports
  EXPECT_NEAR(last(trace.column("box_z")), 0.80, 0.005);
  EXPECT_NEAR(last(trace.column("support_n")), 9.81, 0.5) << "1 kg resting on the table";
  EXPECT_EQ(last(trace.column("left_squeeze_n")), 0.0);

  const auto report = runtime::read_report(dir + "/follower.yaml");
  auto published = [&](const std::string& topic) {
    for (const auto& p : report.published) {
      if (p.topic == topic) return p.sent;
    }
    return uint64_t{0};
  };
  // every cycle publishes both arms' states (how many cycles a loaded ASan build manages in 4 s
  // is not this test's business)
  EXPECT_GT(published("teleop/follower/joint_state/left"), 0u);
  EXPECT_EQ(published("teleop/follower/joint_state/left"), published("teleop/follower/joint_state/right"));
  EXPECT_EQ(published("teleop/follower/joint_state"), 0u) << "no arm on the one-arm topic";
  EXPECT_EQ(report.final_state, "running");
}

}  // namespace
}  // namespace teleop::test
