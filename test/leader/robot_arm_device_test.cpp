// A robot arm as the operator's haptic master (leader.device: robot_arm, robot_arm_device.h): an
// arm of CiA 402 drives carried by g(q) through its CANopen master, turning the emulated drives'
// MuJoCo arm in process (test/emulator/emulated_can_arm.h: the same master and drives the VM runs
// between processes on vcan); a robot whose state is not current, and the configuration.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <string>

#include "emulated_master.h"
#include "robot_arm_device.h"

namespace teleop::leader {
namespace {

constexpr double kPeriodS = 1e-3;

std::string leader_section(const std::string& extra) { return "leader:\n  joints: 7\n" + test::emulated_master_keys(extra); }

std::unique_ptr<LeaderDevice> make_device(const std::string& extra, const std::string& arm_model) {
  const ConfigNode root = ConfigNode::load_string(leader_section(extra), "leader.yaml");
  DeviceSetup setup;
  setup.period_s = kPeriodS;
  setup.arm_model = arm_model;
  return test::emulated_master_devices().parse(root.child("leader"))->make(setup);
}

const std::string kPanda = std::string(TELEOP_SOURCE_DIR) + "/config/models/panda.xml";

// `cycles` of read, then write(feedback); the state after the last read
DeviceState run(LeaderDevice& device, const JointVector& feedback_nm, int cycles) {
  DeviceState state;
  for (int i = 0; i < cycles; ++i) {
    EXPECT_TRUE(device.read(state)) << "cycle " << i;
    EXPECT_TRUE(device.write(feedback_nm)) << "cycle " << i;
  }
  return state;
}

double counter(const LeaderDevice& device, const std::string& name) {
  std::vector<std::pair<std::string, double>> counters;
  device.report_counters(counters);
  for (const auto& [key, value] : counters) {
    if (key == name) return value;
  }
  ADD_FAILURE() << "no counter " << name;
  return -1;
}

TEST(RobotArmDevice, ItsDrivesCarryTheArmsWeightSoThatItStaysWhereTheOperatorLeftIt) {
  const auto device = make_device("", kPanda);
  DeviceState start;
  ASSERT_TRUE(device->read(start));
  const DeviceState after = run(*device, JointVector{}, 1000);
  double drift = 0.0;
  for (size_t k = 0; k < 7; ++k) drift = std::max(drift, std::abs(after.q_rad[k] - start.q_rad[k]));
  EXPECT_LT(drift, 0.005) << "1 s carried by g(q) through the drives";
  EXPECT_EQ(counter(*device, "arm_torque_clamps"), 0.0);
  EXPECT_STREQ(device->name(), "robot_arm:canopen_emulated:can0,can1,can2,can3");

  // the same arm given no torque through the same drives: its weight pulls it down
  robot::HardwareRegistry robots = test::emulated_robots();
  const ConfigNode root = ConfigNode::load_string(leader_section(""), "leader.yaml");
  const auto bare = robots.parse(root.child("leader").child("robot_arm"))->make(kPeriodS);
  robot::ArmState s0;
  robot::ArmState s;
  ASSERT_EQ(bare->read(s0), robot::HardwareStatus::kOk);
  for (int i = 0; i < 1000; ++i) {
    ASSERT_EQ(bare->read(s), robot::HardwareStatus::kOk);
    ASSERT_EQ(bare->write(JointVector{}), robot::HardwareStatus::kOk);
  }
  double fall = 0.0;
  for (size_t k = 0; k < 7; ++k) fall = std::max(fall, std::abs(s.q_rad[k] - s0.q_rad[k]));
  EXPECT_GT(fall, 20 * drift) << "uncarried, the arm falls";
}

TEST(RobotArmDevice, TheRenderedTorqueTurnsTheJointItActsOn) {
  const auto device = make_device("", kPanda);
  DeviceState start;
  ASSERT_TRUE(device->read(start));
  JointVector feedback{};
  feedback[0] = 2.0;  // about the vertical axis: no weight to carry there
  const DeviceState after = run(*device, feedback, 300);
  EXPECT_GT(after.q_rad[0] - start.q_rad[0], 0.05) << "joint 1 turned the way it was pushed";
  // the links beyond lag behind the base's turn (joint 3 counter-turns) but stay up: still carried
  for (size_t k : {1, 3, 5}) EXPECT_LT(std::abs(after.q_rad[k] - start.q_rad[k]), 0.01) << "joint " << k + 1;
  std::printf("joint 1 turned %.3f rad in 0.3 s by 2 N m\n", after.q_rad[0] - start.q_rad[0]);
}

TEST(RobotArmDevice, NoTorqueBeyondTheDevicesBoundEvenToCarryItsWeight) {
  // the joint carrying most of the arm's weight at its start, bound to half of that weight
  const auto free = make_device("", kPanda);
  DeviceState start;
  ASSERT_TRUE(free->read(start));
  ArmKinematics model(kPanda, "ee_site");
  model.update(start.q_rad, start.dq_radps);
  Eigen::Index heaviest = 0;
  model.gravity().cwiseAbs().maxCoeff(&heaviest);
  const auto j = static_cast<size_t>(heaviest);
  ASSERT_GT(std::abs(model.gravity()[heaviest]), 5.0);
  std::string bound = "    max_torque_nm: [";
  for (size_t k = 0; k < 7; ++k) {
    bound += (k ? ", " : "") + std::to_string(k == j ? std::abs(model.gravity()[heaviest]) / 2 : 87.0);
  }
  const auto device = make_device(bound + "]\n", kPanda);
  ASSERT_TRUE(device->read(start));
  const DeviceState after = run(*device, JointVector{}, 200);
  EXPECT_EQ(counter(*device, "arm_torque_clamps"), 200.0) << "every cycle";
  EXPECT_GT(std::abs(after.q_rad[j] - start.q_rad[j]), 0.01) << "bound below its weight, joint " << j + 1 << " sags";
}

TEST(RobotArmDevice, AnArmThatDoesNotCarryItsWeightNeedsItsModel) {
  try {
    (void)make_device("", "");
    FAIL() << "made without a model for g(q)";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("leader.robot_arm.gravity_model"), std::string::npos) << e.what();
  }
}

TEST(RobotArmDevice, AnUnknownRobotBackendIsAConfigurationErrorNamingTheKey) {
  const ConfigNode root = ConfigNode::load_string(
      "leader:\n  joints: 7\n  device: robot_arm\n  robot_arm: {hardware: canopn}\n", "leader.yaml");
  try {
    (void)test::emulated_master_devices().parse(root.child("leader"));
    FAIL() << "parsed";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("hardware"), std::string::npos) << e.what();
  }
}

// a robot whose state is stale, then current again, counting what it was asked
class StaleRobot final : public robot::RobotHardware {
 public:
  size_t joints() const override { return 7; }
  robot::HardwareStatus read(robot::ArmState& state) override {
    state.q_rad[0] = 0.5;
    state.dq_radps[3] = 0.25;
    return status;
  }
  robot::HardwareStatus write(const JointVector& tau_nm) override {
    last_nm = tau_nm;
    ++writes;
    return robot::HardwareStatus::kOk;
  }
  robot::HardwareStatus hold() override {
    ++holds;
    return robot::HardwareStatus::kOk;
  }
  bool compensates_gravity() const override { return true; }
  robot::HardwareLimits limits() const override {
    robot::HardwareLimits l;
    l.max_torque_nm.fill(10.0);
    return l;
  }
  const char* name() const override { return "stale"; }

  robot::HardwareStatus status = robot::HardwareStatus::kStale;
  JointVector last_nm{};
  int writes = 0;
  int holds = 0;
};

TEST(RobotArmDevice, AStateThatIsNotCurrentIsALostDeviceHeldByTheRobotsOwnMeansAndTheRestIsRendered) {
  auto owned = std::make_unique<StaleRobot>();
  StaleRobot& robot = *owned;
  JointVector bound{};
  bound.fill(std::numeric_limits<double>::infinity());
  JointVector damping{};
  damping[3] = 2.0;
  RobotArmDevice device(std::move(owned), nullptr, bound, damping);
  DeviceState state;
  JointVector feedback{};
  feedback[0] = 3.0;
  EXPECT_FALSE(device.read(state));
  EXPECT_TRUE(device.write(feedback));
  EXPECT_EQ(robot.holds, 1) << "held, not given a torque computed from an old state";
  EXPECT_EQ(robot.writes, 0);
  robot.status = robot::HardwareStatus::kFault;
  EXPECT_FALSE(device.read(state));
  robot.status = robot::HardwareStatus::kOk;
  ASSERT_TRUE(device.read(state));
  EXPECT_EQ(state.q_rad[0], 0.5);
  feedback[1] = std::numeric_limits<double>::quiet_NaN();
  feedback[2] = 25.0;
  EXPECT_TRUE(device.write(feedback));
  EXPECT_EQ(robot.last_nm[0], 3.0) << "a robot carrying its weight itself gets the feedback alone";
  EXPECT_EQ(robot.last_nm[1], 0.0) << "not finite: nothing";
  EXPECT_EQ(robot.last_nm[2], 10.0) << "the robot's own limit";
  EXPECT_EQ(robot.last_nm[3], -0.5) << "the damping rendered against the joint's motion";
  EXPECT_EQ(counter(device, "arm_stale_reads"), 1.0);
  EXPECT_EQ(counter(device, "arm_fault_reads"), 1.0);
  EXPECT_EQ(counter(device, "arm_holds"), 1.0);
  EXPECT_EQ(counter(device, "arm_torque_clamps"), 1.0);
}

}  // namespace
}  // namespace teleop::leader
