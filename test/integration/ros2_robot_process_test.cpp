// The follower teleoperating a ROS 2 robot it shares no code with: the stand-in robot on Cyclone DDS
// (test/robot/ros2/standin_robot.cpp: a MuJoCo arm behind ros2_control's topics and types),
// configured as the shipped Franka example (config/nodes/follower_franka_ros2.yaml) on a domain of
// its own. The same leader script drives the follower on the MuJoCo backend for reference, and
// the stiff wall's experiment runs on both (config/experiments/stiff_wall.yaml on `lan`).
#include <gtest/gtest.h>

#include <csignal>
#include <cstdlib>

#include "process_helpers.h"
#include "results_row.h"
#include "stiff_wall_runs.h"
#include "report_counter.h"
#include "teleop/runtime/node_report.h"

namespace teleop::test {
namespace {

using namespace std::chrono_literals;

constexpr const char* kJoints = "fr3_joint1,fr3_joint2,fr3_joint3,fr3_joint4,fr3_joint5,fr3_joint6,fr3_joint7";

struct Robot {
  std::string interface = "effort";
  bool shuffle = false;
  double pause_at_s = -1;  // after the first command
  bool wrench = false;     // the robot publishes its contact wrench, the follower estimates from it
  // the robot publishes its contact wrench, the follower's ground truth (as the simulation's is)
  // while it estimates by its observer
  bool wrench_as_truth = false;
};

constexpr const char* kWrenchTopic = "/franka_robot_state_broadcaster/external_wrench_in_base_frame";

struct Site : ProcessSite {
  int robot_domain = unique_domain();

  // the Franka example on this test's robot domain, found by unicast on loopback (as the stand-in is)
  std::string follower_config(const Robot& robot) const {
    std::vector<std::pair<std::string, std::string>> edits = {
        {"      domain_id: 0\n", "      domain_id: " + std::to_string(robot_domain) +
                                     "\n      initial_peers: [127.0.0.1]\n      interface_whitelist: [127.0.0.1]\n"}};
    if (robot.interface != "effort") {
      edits.push_back({"interface: effort", "interface: " + robot.interface});
      edits.push_back({"/forward_effort_controller/", "/forward_" + robot.interface + "_controller/"});
    }
    if (robot.wrench || robot.wrench_as_truth) {
      edits.push_back({"    wrench_topic: \"\"", std::string("    wrench_topic: ") + kWrenchTopic});
      edits.push_back({"    wrench_frame: \"\"", "    wrench_frame: fr3_link0"});
    }
    if (robot.wrench) edits.push_back({"published_estimate: momentum_observer", "published_estimate: hardware"});
    return config_copy(dir, "follower_franka_ros2.yaml", edits);
  }

  std::vector<std::string> standin(const Robot& robot, double duration_s) const {
    std::vector<std::string> argv = {bin("teleop_ros2_standin_robot"), "--model", source("config/models/scene_wall.xml"),
                                     "--keyframe", "facing_wall", "--joints", kJoints, "--domain",
                                     std::to_string(robot_domain), "--interface", robot.interface,
                                     "--duration-s", std::to_string(duration_s)};
    // the gripper's joint the example ignores, first, and the arm's joints reversed
    if (robot.shuffle) argv.insert(argv.end(), {"--shuffle", "--extra-joint", "fr3_finger_joint1"});
    if (robot.wrench || robot.wrench_as_truth) argv.insert(argv.end(), {"--wrench-topic", kWrenchTopic});
    if (robot.pause_at_s >= 0) argv.insert(argv.end(), {"--pause-at-s", std::to_string(robot.pause_at_s), "--pause-ms", "50"});
    return argv;
  }

  // the shipped leader's sine, which presses the flange into the wall, for 6 s
  void run_leader(const std::string& tag) const {
    std::vector<std::string> leader = args("leader", source("config/nodes/leader.yaml"), tag);
    leader.insert(leader.end(), {"--duration", "6"});
    const ProcessResult result = run_process(leader, 60s);
    ASSERT_EQ(result.exit_status, 0) << result.output;
  }

  // a follower that outlives the leader by a second or so, then ends by itself
  std::vector<std::string> follower(const std::string& config, const std::string& tag) const {
    std::vector<std::string> argv = args("follower", config, tag);
    argv.insert(argv.end(), {"--duration", "30"});
    return argv;
  }
};

// the peak contact force the follower reported against the simulation's under the same script
void expect_same_peak_contact(const runtime::NodeReport& ros2, const runtime::NodeReport& mujoco) {
  const double reference = counter(mujoco, "peak_external_force_n");
  EXPECT_GT(reference, 10.0) << "the leader's sine presses the wall";
  EXPECT_NEAR(counter(ros2, "peak_external_force_n"), reference, 0.1 * reference)
      << "peak contact force of the ROS 2 robot against the MuJoCo backend's";
  ::testing::Test::RecordProperty("peak_force_ratio", std::to_string(counter(ros2, "peak_external_force_n") / reference));
}

struct Outcome {
  runtime::NodeReport follower;
  std::string follower_log;
  std::string robot_log;
};

// teleoperation of the stand-in robot: the follower is stopped (SIGTERM) once the leader ended
Outcome teleoperate_ros2_robot(const Site& site, const Robot& robot, const std::string& tag) {
  RunningProcess standin(site.standin(robot, 60));
  EXPECT_TRUE(standin.wait_for_output("robot of 7 joints", 20s)) << standin.output();
  RunningProcess follower(site.follower(site.follower_config(robot), tag));
  EXPECT_TRUE(follower.wait_for_output("starting\n", 30s)) << follower.output();
  site.run_leader("leader_" + tag);
  follower.run_for(500ms);
  EXPECT_EQ(follower.stop(SIGTERM, 20s), 0) << follower.output();
  // the follower's last word to the controller is the hold; the robot then times out on its own
  EXPECT_TRUE(standin.wait_for_output("command timeout: holding", 10s)) << standin.output();
  (void)standin.stop(SIGTERM, 10s);
  // the robot's account of the commands it got, for the log
  const size_t summary = standin.output().rfind("standin: commands");
  if (summary != std::string::npos) std::printf("%s", standin.output().substr(summary).c_str());
  return {runtime::read_report(site.report_path(tag)), follower.output(), standin.output()};
}

// `estimate`: the follower's published_estimate (the simulation's ground truth is `hardware`)
runtime::NodeReport teleoperate_mujoco_robot(const Site& site, const std::string& estimate = "momentum_observer") {
  const std::string config =
      config_copy(site.dir, "follower.yaml", {{"published_estimate: momentum_observer", "published_estimate: " + estimate}});
  RunningProcess follower(site.follower(config, "mujoco"));
  EXPECT_TRUE(follower.wait_for_output("starting\n", 30s)) << follower.output();
  site.run_leader("leader_mujoco");
  follower.run_for(500ms);
  EXPECT_EQ(follower.stop(SIGTERM, 20s), 0) << follower.output();
  return runtime::read_report(site.report_path("mujoco"));
}

TEST(Ros2Robot, EffortRobotWithShuffledJointsTouchesTheWallAsTheSimulation) {
  Site site;
  const Outcome ros2 = teleoperate_ros2_robot(site, {"effort", true, -1}, "ros2");
  const runtime::NodeReport mujoco = teleoperate_mujoco_robot(site);
  EXPECT_EQ(counter(ros2.follower, "hardware_faults"), 0.0) << ros2.follower_log;
  // the shuffled names are mapped: the wall contact is the simulation's
  expect_same_peak_contact(ros2.follower, mujoco);
  // recorded, not compared (docs/robots.md): a speed reflex held the arm for the rest of the run in
  // 3 of 14 runs before the follower's cycle was locked to the robot's, none in 9 since
  ::testing::Test::RecordProperty("reflex_trips", std::to_string(counter(ros2.follower, "reflex_trips")));
  EXPECT_GT(counter(ros2.follower, "tracking_rmse_rad"), 0.0);
  ::testing::Test::RecordProperty("tracking_rmse_ratio", std::to_string(counter(ros2.follower, "tracking_rmse_rad") /
                                                                         counter(mujoco, "tracking_rmse_rad")));
  EXPECT_NE(ros2.robot_log.find("wrong size 0"), std::string::npos) << ros2.robot_log;
}

TEST(Ros2Robot, TheRobotsMeasuredWrenchIsTheContactTheSimulationReports) {
  Site site;
  const Outcome ros2 = teleoperate_ros2_robot(site, {"effort", false, -1, true}, "ros2_wrench");
  const runtime::NodeReport mujoco = teleoperate_mujoco_robot(site, "hardware");
  EXPECT_EQ(counter(ros2.follower, "robot_wrenches_refused"), 0.0);
  // the follower's wrench from the robot's (J^T w, then back) against the simulation's contact
  expect_same_peak_contact(ros2.follower, mujoco);
}

TEST(Ros2Robot, FollowerHoldsWhileTheRobotsStateStopsAndResumesAfter) {
  Site site;
  const Outcome ros2 = teleoperate_ros2_robot(site, {"effort", false, 2.0}, "ros2_paused");
  EXPECT_EQ(counter(ros2.follower, "hardware_faults"), 0.0) << ros2.follower_log;
  // 50 ms without the robot's state: a hold, and the commands are followed again after it
  ASSERT_NE(ros2.robot_log.find("state paused for 50 ms"), std::string::npos) << ros2.robot_log;
  EXPECT_GE(counter(ros2.follower, "robot_state_holds"), 1.0);
  EXPECT_GE(counter(ros2.follower, "robot_stale_cycles"), 20.0) << "50 ms of silence, 20 ms of them tolerated";
  const size_t hold = ros2.follower_log.find("running -> safe_hold (stale_input)");
  ASSERT_NE(hold, std::string::npos) << ros2.follower_log;
  EXPECT_NE(ros2.follower_log.find("safe_hold -> running", hold), std::string::npos) << ros2.follower_log;
}

TEST(Ros2Robot, PositionRobotFollowsTheJointReference) {
  Site site;
  const Outcome ros2 = teleoperate_ros2_robot(site, {"position", false, -1}, "ros2_position");
  EXPECT_EQ(counter(ros2.follower, "hardware_faults"), 0.0) << ros2.follower_log;
  EXPECT_EQ(counter(ros2.follower, "robot_state_holds"), 0.0) << ros2.follower_log;
  EXPECT_GT(counter(ros2.follower, "tracking_rmse_rad"), 0.0);
  EXPECT_LT(counter(ros2.follower, "tracking_rmse_rad"), 0.05) << "the robot's own position loop tracks the reference";
  EXPECT_NE(ros2.robot_log.find("wrong size 0"), std::string::npos) << ros2.robot_log;
}

TEST(Ros2Robot, KilledFollowerLeavesTheRobotHoldingWithinItsCommandTimeout) {
  Site site;
  const Robot robot;
  RunningProcess standin(site.standin(robot, 60));
  ASSERT_TRUE(standin.wait_for_output("robot of 7 joints", 20s)) << standin.output();
  RunningProcess follower(site.follower(site.follower_config(robot), "killed"));
  ASSERT_TRUE(follower.wait_for_output("starting\n", 30s)) << follower.output();
  std::vector<std::string> leader_args = site.args("leader", source("config/nodes/leader.yaml"), "leader");
  RunningProcess leader(leader_args);
  ASSERT_TRUE(standin.wait_for_output("commanded at", 30s)) << standin.output() << follower.output();
  standin.run_for(1500ms);  // mid-motion
  (void)follower.stop(SIGKILL, 10s);
  // the stand-in holds once 100 ms passed without a command (its --command-timeout-ms), and stops
  ASSERT_TRUE(standin.wait_for_output("stopped", 10s)) << standin.output();
  (void)leader.stop(SIGTERM, 10s);
  (void)standin.stop(SIGTERM, 10s);
  const std::string& log = standin.output();
  const size_t holding = log.find("command timeout: holding ");
  ASSERT_NE(holding, std::string::npos) << log;
  const double held_after_ms = std::strtod(log.c_str() + holding + std::string("command timeout: holding ").size(), nullptr);
  EXPECT_GE(held_after_ms, 100.0);
  EXPECT_LE(held_after_ms, 150.0) << "the robot reacts at its command timeout";
}

TEST(Ros2Robot, ShippedConfigStartsAndNamesTheRobotItDoesNotFind) {
  Site site;
  std::vector<std::string> argv = site.args("follower", source("config/nodes/follower_franka_ros2.yaml"), "absent");
  argv.insert(argv.end(), {"--set", "follower.ros2.connect_timeout_s=0.5", "--set",
                           "follower.ros2.transport.domain_id=" + std::to_string(site.robot_domain)});
  const ProcessResult result = run_process(argv, 60s);
  EXPECT_NE(result.exit_status, 0);
  EXPECT_NE(result.output.find("no sensor_msgs/JointState on /joint_states within ros2.connect_timeout_s"), std::string::npos)
      << result.output;
}

// The stiff wall of config/experiments/stiff_wall.yaml, one architecture on `lan`: its row on the
// MuJoCo backend, and with the follower on the stand-in robot (a fresh one, at the same pose in
// front of the same wall), whose contact wrench is then the ground truth the analysis reads
struct StiffWallRows {
  ResultsRow mujoco;
  ResultsRow ros2;
};

StiffWallRows stiff_wall_on_both(const std::string& architecture) {
  Site site;
  StiffWallRows rows;
  rows.mujoco = run_stiff_wall(site, source("config/experiments/stiff_wall.yaml"), architecture, "mujoco");
  // the experiment and its scenario beside the Franka config, which replaces the follower's
  Robot robot;
  robot.wrench_as_truth = true;
  (void)site.follower_config(robot);
  const std::string experiment = stiff_wall_with_follower(site, "teleop_follower", "follower_franka_ros2.yaml");
  RunningProcess standin(site.standin(robot, 120));
  EXPECT_TRUE(standin.wait_for_output("robot of 7 joints", 20s)) << standin.output();
  rows.ros2 = run_stiff_wall(site, experiment, architecture, "ros2");
  (void)standin.stop(SIGTERM, 10s);
  return rows;
}

// the table's verdict, the force the operator feels and how far the follower is off its reference
// in the hold: within 10 % of the simulation's. The force exerted is not the same quantity: the
// robot's is its flange's contact wrench (a force sensor's), the simulation's every constraint
// force on the joints (J^T+ of MuJoCo's qfrc_constraint), its joint friction included, which holds
// part of the push: 0.86-0.93 of it measured
void expect_same_stiff_wall(const StiffWallRows& rows) {
  ASSERT_EQ(rows.mujoco.at("status"), "ok");
  ASSERT_EQ(rows.ros2.at("status"), "ok");
  EXPECT_EQ(rows.ros2.at("stable"), rows.mujoco.at("stable")) << rows.ros2.at("stable_why");
  for (const char* column : {"force_felt_n", "tracking_hold_m"}) {
    const double simulation = number(rows.mujoco, column);
    EXPECT_NEAR(number(rows.ros2, column), simulation, 0.1 * simulation) << column;
  }
  const double exerted = number(rows.ros2, "force_exerted_n") / number(rows.mujoco, "force_exerted_n");
  EXPECT_GT(exerted, 0.8);
  EXPECT_LT(exerted, 1.02);
  ::testing::Test::RecordProperty("force_exerted_ratio", std::to_string(exerted));
}

// Position-position holds where it lands: 9.5-15.5 N felt over four runs on the robot against
// 15.0-15.1 N on the simulation. The low runs are those where the follower joined a second late,
// still discovering the robot, while the scripted operator already pushed (docs/robots.md). What
// holds in every run: the verdict, and the operator feels what the robot exerts (off by its joint
// friction, as above)
TEST(Ros2Robot, StiffWallPositionPositionIsStableAndFeelsWhatTheRobotExerts) {
  const StiffWallRows rows = stiff_wall_on_both("position_position");
  ASSERT_EQ(rows.mujoco.at("status"), "ok");
  ASSERT_EQ(rows.ros2.at("status"), "ok");
  EXPECT_EQ(rows.ros2.at("stable"), "yes") << rows.ros2.at("stable_why");
  EXPECT_GT(number(rows.ros2, "force_exerted_n"), 5.0) << "the robot presses on the wall";
  EXPECT_LT(number(rows.ros2, "force_error_n"), 0.15 * number(rows.ros2, "force_felt_n"));
  ::testing::Test::RecordProperty("force_felt_ratio",
                                  std::to_string(number(rows.ros2, "force_felt_n") / number(rows.mujoco, "force_felt_n")));
}

TEST(Ros2Robot, StiffWallPfcAsOnTheSimulation) { expect_same_stiff_wall(stiff_wall_on_both("pfc")); }

TEST(Ros2Robot, StiffWallPfcTdpaAsOnTheSimulation) { expect_same_stiff_wall(stiff_wall_on_both("pfc_tdpa")); }

TEST(Ros2Robot, StiffWallModelMediatedAsOnTheSimulation) { expect_same_stiff_wall(stiff_wall_on_both("mmt")); }

}  // namespace
}  // namespace teleop::test
