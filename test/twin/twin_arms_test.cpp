// The two-arm twin (twin.arms): its configuration, and its node over DDS with each arm coupled
// to its own leader arm on the per-arm topics (T/left, T/right).
#include "twin_arms.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "allocation_counter.h"
#include "node_harness.h"
#include "teleop/transport/arm_topic.h"
#include "teleop/transport/joint_fields.h"
#include "twin_node_test_util.h"
#include "twin_test_util.h"

namespace teleop::twin {
namespace {

constexpr size_t kJoints = 7;
constexpr size_t kWrist = 6;  // the flange's joint: turning it moves nothing into anything
constexpr double kWristLimitRad = 2.8973;

// the box task's twin: both arms of scene_box_shelf.xml; `twin_keys` go into the twin section
std::string box_task_yaml(const std::string& twin_keys = "", const std::string& architecture = "mmt") {
  return "teleoperation: {architecture: " + architecture +
         "}\n"
         "twin:\n  joints: 7\n  feedback_cutoff_hz: 0\n  feedback_gain: 0.5\n" +
         twin_keys + "  model:\n    file: " + test::model_path("scene_box_shelf.xml") +
         "\n    keyframe: home\n"
         "  arms:\n    left: {joint_prefix: left_}\n    right: {joint_prefix: right_}\n";
}

std::string error_of(const std::string& yaml) {
  return test::config_error(parse_twin_arms, yaml, "twin_box_task.yaml");
}

TEST(TwinArmsConfig, GivesOneConfigPerArmWithItsPrefix) {
  const auto arms = parse_twin_arms(ConfigNode::load_string(box_task_yaml(), "twin_box_task.yaml"));
  ASSERT_EQ(arms.size(), 2u);
  EXPECT_EQ(arms[0].arm, "left");
  EXPECT_EQ(arms[0].joint_prefix, "left_");
  EXPECT_EQ(arms[1].arm, "right");
  EXPECT_EQ(arms[1].joint_prefix, "right_");
  EXPECT_TRUE(arms[1].mmt.enabled);
  EXPECT_DOUBLE_EQ(arms[1].feedback_gain, 0.5) << "the shared section applies to every arm";
}

TEST(TwinArmsConfig, WithoutArmsIsTheOneUnnamedArm) {
  const std::string yaml = "twin:\n  joints: 7\n  model:\n    file: " + test::model_path("scene_wall.xml") + "\n";
  const auto arms = parse_twin_arms(ConfigNode::load_string(yaml, "twin.yaml"));
  ASSERT_EQ(arms.size(), 1u);
  EXPECT_TRUE(arms[0].arm.empty());
}

TEST(TwinArmsConfig, RefusesTheOneArmModesAndCorrectionWithArms) {
  const std::string lockstep = error_of(box_task_yaml("  mode: lockstep\n", "position_position"));
  EXPECT_NE(lockstep.find("twin_box_task.yaml"), std::string::npos) << lockstep;
  EXPECT_NE(lockstep.find("twin.arms"), std::string::npos) << lockstep;
  EXPECT_NE(lockstep.find("lockstep"), std::string::npos) << lockstep;
  const std::string hil =
      error_of(box_task_yaml("  mode: hil\n  hil: {goal_rad: [0, 0, 0, 0, 0, 0, 0]}\n", "position_position"));
  EXPECT_NE(hil.find("twin.arms"), std::string::npos) << hil;
  const std::string correction =
      error_of(box_task_yaml("  mmt:\n    correction: {geom: box, normal: [0, 1, 0]}\n"));
  EXPECT_NE(correction.find("twin.mmt.correction"), std::string::npos) << correction;
  EXPECT_NE(correction.find("one arm"), std::string::npos) << correction;
}

TEST(TwinArmsConfig, ReadsTheObjectCorrectionAndRefusesItWithoutArms) {
  const auto arms = parse_twin_arms(ConfigNode::load_string(
      box_task_yaml("  object_correction: {bodies: [box], stiffness_n_per_m: 300, max_force_n: 5, timeout_ms: 50}\n"),
      "twin_box_task.yaml"));
  ASSERT_TRUE(arms[0].object_correction.has_value());
  EXPECT_EQ(arms[0].object_correction->bodies, std::vector<std::string>{"box"});
  EXPECT_DOUBLE_EQ(arms[0].object_correction->stiffness_n_per_m, 300.0);
  EXPECT_DOUBLE_EQ(arms[0].object_correction->max_force_n, 5.0);
  EXPECT_DOUBLE_EQ(arms[0].object_correction->timeout_s, 0.05);
  EXPECT_DOUBLE_EQ(arms[0].object_correction->damping_ns_per_m, ObjectCorrectionConfig{}.damping_ns_per_m);
  const std::string one_arm = test::config_error(
      parse_twin_arms,
      "twin:\n  joints: 7\n  model:\n    file: " + test::model_path("scene_wall.xml") +
          "\n  object_correction: {bodies: [box]}\n",
      "twin.yaml");
  EXPECT_NE(one_arm.find("twin.object_correction"), std::string::npos) << one_arm;
  EXPECT_NE(one_arm.find("twin.arms"), std::string::npos) << one_arm;
  const std::string no_bodies = error_of(box_task_yaml("  object_correction: {bodies: []}\n"));
  EXPECT_NE(no_bodies.find("twin.object_correction.bodies"), std::string::npos) << no_bodies;
}

TEST(TwinArmsConfig, RefusesAnArmWithoutPrefix) {
  std::string yaml = box_task_yaml();
  yaml.replace(yaml.find("{joint_prefix: right_}"), 22, "{joint_prefix: \"\"}");
  const std::string e = error_of(yaml);
  EXPECT_NE(e.find("twin.arms.right.joint_prefix"), std::string::npos) << e;
}

// one leader arm's side: publishes its device state, reads what the twin sends that arm
struct LeaderArm {
  transport::Publication<msg::JointState> state;
  transport::Subscription<msg::JointTorque> feedback;
  transport::Subscription<msg::JointState> twin_state;
  transport::Subscription<msg::JointCommand> command;
  LeaderArm(transport::Participant& p, const std::string& arm)
      : state(p, transport::arm_topic(transport::topics::kLeaderState, arm), "leader"),
        feedback(p, transport::arm_topic(transport::topics::kTwinFeedback, arm)),
        twin_state(p, transport::arm_topic(transport::topics::kTwinState, arm)),
        command(p, transport::arm_topic(transport::topics::kTwinCommand, arm)) {
    transport::presize_joint_state(state.sample(), kJoints);
  }
  bool matched() const {
    return state.matched() > 0 && feedback.reader().matched() > 0 && twin_state.reader().matched() > 0 &&
           command.reader().matched() > 0;
  }
  // the newest value of `field` of the newest sample of `sub`
  template <typename T, typename Field>
  static double newest(transport::Subscription<T>& sub, Field field, size_t joint) {
    double value = std::nan("");
    teleop::test::eventually([&] {
      sub.poll();
      if (sub.has_sample()) value = field(sub.latest())[joint];
      return sub.has_sample();
    });
    return value;
  }
};

class TwinArmsNodeTest : public ::testing::Test {
 protected:
  // the remote site's box pulls the twin's (hard enough to lift it, for the test)
  static constexpr const char* kObjectCorrection =
      "  object_correction: {bodies: [box], stiffness_n_per_m: 1000, damping_ns_per_m: 60, max_force_n: 40}\n";
  teleop::test::NodeHarness harness{"twin"};
  std::unique_ptr<runtime::NodeLogic> node = twin_logic_parser()(
      ConfigNode::load_string(box_task_yaml(kObjectCorrection), "twin_box_task.yaml"))(harness.context);
  transport::Publication<msg::ObjectPose> remote_box{
      harness.peer, transport::TopicSpec<msg::ObjectPose>{"teleop/follower/object_pose/box", transport::QosPreset::kStream},
      "follower"};
  LeaderArm left{harness.peer, "left"};
  LeaderArm right{harness.peer, "right"};
  // the keyframe "home" of scene_box_shelf.xml
  JointVector left_home{-0.066, 0.739, -0.020, -2.103, 0.044, 2.839, 0.0};
  JointVector right_home{0.066, 0.739, 0.020, -2.103, -0.044, 2.839, 0.0};

  void SetUp() override {
    ASSERT_TRUE(
        teleop::test::eventually([&] { return left.matched() && right.matched() && remote_box.matched() > 0; }));
  }

  // the twin's counter `name` (-1: absent)
  double counter(const std::string& name) const {
    runtime::NodeReport report;
    node->fill_report(report);
    for (const auto& [n, v] : report.counters) {
      if (n == name) return v;
    }
    return -1.0;
  }

  // each arm's leader at its pose (`publish_right` false: the right leader is silent); returns
  // the cycles' allocations
  uint64_t hold(const JointVector& left_q, const JointVector& right_q, int cycles, bool publish_right = true) {
    return test::drive_cycles(*node, harness, cycles, [&](int) {
      transport::copy_joints(left_q, kJoints, left.state.sample().q_rad());
      EXPECT_TRUE(left.state.publish());
      if (!publish_right) return;
      transport::copy_joints(right_q, kJoints, right.state.sample().q_rad());
      EXPECT_TRUE(right.state.publish());
    });
  }
};

TEST_F(TwinArmsNodeTest, EachArmFollowsItsOwnLeaderArm) {
  JointVector left_q = left_home;
  JointVector right_q = right_home;
  left_q[kWrist] += 0.4;
  right_q[4] -= 0.3;
  // the leaders are heard at home first: a twin joins its leader from where it stands at a calm
  // speed (coupled_robot.h), and follows it as it is once joined
  hold(left_home, right_home, 50);
  hold(left_q, right_q, 500);
  EXPECT_EQ(node->state(), msg::STATE_RUNNING);
  auto q = [](const msg::JointState& s) { return s.q_rad(); };
  EXPECT_NEAR(LeaderArm::newest(left.twin_state, q, kWrist), left_q[kWrist], 0.01);
  EXPECT_NEAR(LeaderArm::newest(left.twin_state, q, 4), left_home[4], 0.01) << "the right leader's motion";
  EXPECT_NEAR(LeaderArm::newest(right.twin_state, q, 4), right_q[4], 0.01);
  EXPECT_NEAR(LeaderArm::newest(right.twin_state, q, kWrist), right_home[kWrist], 0.01);
  // MMT: each follower arm is commanded to its own twin arm
  auto q_des = [](const msg::JointCommand& c) { return c.q_des_rad(); };
  EXPECT_NEAR(LeaderArm::newest(left.command, q_des, kWrist), left_q[kWrist], 0.01);
  EXPECT_NEAR(LeaderArm::newest(right.command, q_des, 4), right_q[4], 0.01);
  EXPECT_EQ(std::string(left.command.latest().arm()), "left");
  EXPECT_EQ(std::string(right.command.latest().arm()), "right");
}

TEST_F(TwinArmsNodeTest, RendersAnArmsConstraintOnlyToItsOwnLeaderArm) {
  // the left leader turns its wrist past the joint's limit: the twin's left wrist stops there
  JointVector left_q = left_home;
  left_q[kWrist] = kWristLimitRad + 0.1;
  hold(left_home, right_home, 50);  // joined at home first (coupled_robot.h)
  hold(left_q, right_home, 700);
  auto tau = [](const msg::JointTorque& t) { return t.tau_nm(); };
  const double left_fb = LeaderArm::newest(left.feedback, tau, kWrist);
  // 0.5 * 300 N m/rad * 0.1 rad (lambda, the coupling's default K, the overshoot), less what the
  // limit's softness lets through
  EXPECT_LT(left_fb, -5.0) << "the limit pushes the left hand back";
  double right_peak = 0;
  for (size_t j = 0; j < kJoints; ++j) right_peak = std::max(right_peak, std::abs(LeaderArm::newest(right.feedback, tau, j)));
  EXPECT_LT(right_peak, 0.05) << "the right hand, free at home, feels nothing of it";
  EXPECT_EQ(node->state(), msg::STATE_RUNNING);
}

TEST_F(TwinArmsNodeTest, ASilentArmAloneGoesToSafeHold) {
  hold(left_home, right_home, 100);
  ASSERT_EQ(node->state(), msg::STATE_RUNNING);
  // the right leader falls silent for longer than the peer timeout (100 ms)
  hold(left_home, right_home, 400, false);
  EXPECT_EQ(node->state(), msg::STATE_SAFE_HOLD);
  std::vector<uint32_t> faults;
  node->active_faults(faults);
  EXPECT_EQ(std::count(faults.begin(), faults.end(), msg::FAULT_PEER_LOST), 1) << "one arm lost its peer";
  // from now on the right arm commands its follower arm no more; the left one goes on
  auto newest_seq = [](transport::Subscription<msg::JointCommand>& sub) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    sub.poll();
    return sub.has_sample() ? sub.latest().header().seq() : 0;
  };
  const uint64_t right_before = newest_seq(right.command);
  const uint64_t left_before = newest_seq(left.command);
  hold(left_home, right_home, 100, false);
  EXPECT_EQ(newest_seq(right.command), right_before);
  EXPECT_GT(newest_seq(left.command), left_before + 50) << "about one command a cycle";
  EXPECT_EQ(counter("left.rejected_samples"), 0.0);
  EXPECT_GE(counter("sim_time_s"), 0.5) << "the scene's counters keep the one-arm twin's names";
  EXPECT_EQ(counter("mujoco_warnings"), 0.0);
}

TEST_F(TwinArmsNodeTest, TheRemoteBoxMeasuredHigherPullsTheTwinsBoxUp) {
  // the box (1 kg) rests in its socket at z = 0.80; the remote site measures it 5 cm higher. At
  // 1000 N/m it settles ~1 cm below the target (its weight); the socket's walls keep x and y.
  std::vector<std::string> columns;
  node->trace_columns(columns);
  const auto column = [&](const std::string& name) {
    return static_cast<size_t>(std::find(columns.begin(), columns.end(), name) - columns.begin());
  };
  ASSERT_LT(column("object_box_error_m"), columns.size());
  ASSERT_LT(column("object_box_force_n"), columns.size());
  std::vector<double> row(columns.size());
  // both leader arms hold home; the remote box is measured higher every cycle; returns allocations
  const auto run = [&](int cycles) {
    return test::drive_cycles(*node, harness, cycles, [&](int) {
      remote_box.sample().body("box");
      remote_box.sample().world_pose().position_m().x(0.35);
      remote_box.sample().world_pose().position_m().z(0.85);
      remote_box.sample().world_pose().orientation().w(1.0);
      EXPECT_TRUE(remote_box.publish());
      transport::copy_joints(left_home, kJoints, left.state.sample().q_rad());
      EXPECT_TRUE(left.state.publish());
      transport::copy_joints(right_home, kJoints, right.state.sample().q_rad());
      EXPECT_TRUE(right.state.publish());
    });
  };
  for (int i = 0; i < 500 && counter("object_box_accepted") <= 0; ++i) run(1);
  node->trace_row(row.data());
  EXPECT_NEAR(row[column("object_box_error_m")], 0.05, 0.005) << "the first measurement finds the box resting";
  run(50);  // every arm's first samples in, every buffer at size
  EXPECT_EQ(run(1450), 0u) << "allocations";
  node->trace_row(row.data());
  EXPECT_LT(row[column("object_box_error_m")], 0.02) << "lifted towards the measurement";
  EXPECT_GT(row[column("object_box_force_n")], 5.0) << "holding it against its weight";
  EXPECT_GT(counter("object_box_accepted"), 1000.0);
  EXPECT_EQ(counter("object_box_rejected"), 0.0);
  EXPECT_EQ(counter("mujoco_warnings"), 0.0);
}

TEST_F(TwinArmsNodeTest, ASampleNamingAnotherBodyPullsNothing) {
  test::drive_cycles(*node, harness, 300, [&](int) {
    remote_box.sample().body("crate");  // a publisher on the wrong topic
    remote_box.sample().header().stamp_ns(system_now_ns());
    remote_box.sample().world_pose().position_m().z(0.85);
    remote_box.sample().world_pose().orientation().w(1.0);
    EXPECT_TRUE(remote_box.publish());
  });
  EXPECT_GT(counter("object_box_wrong_body"), 100.0);
  EXPECT_EQ(counter("object_box_accepted"), 0.0);
  std::vector<std::string> columns;
  node->trace_columns(columns);
  std::vector<double> row(columns.size());
  node->trace_row(row.data());
  const size_t force = static_cast<size_t>(std::find(columns.begin(), columns.end(), "object_box_force_n") - columns.begin());
  ASSERT_LT(force, columns.size());
  EXPECT_EQ(row[force], 0.0);
}

TEST_F(TwinArmsNodeTest, NamesTraceColumnsPerArm) {
  std::vector<std::string> columns;
  node->trace_columns(columns);
  for (const char* c : {"left_state", "left_q_6", "left_tau_fb_0", "left_coupling_error_rad", "right_state", "right_q_0"}) {
    EXPECT_NE(std::find(columns.begin(), columns.end(), c), columns.end()) << c;
  }
}

TEST_F(TwinArmsNodeTest, CyclesWithoutAllocating) {
  hold(left_home, right_home, 50);  // first samples in, every buffer at size
  EXPECT_EQ(hold(left_home, right_home, 200), 0u);
}

}  // namespace
}  // namespace teleop::twin
