#include "teleop/robot/mujoco_hardware.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "allocation_counter.h"
#include "teleop/common/config.h"
#include "teleop/robot/mujoco_backend.h"
#include "test_helpers.h"

namespace teleop::robot {
namespace {

MujocoHardwareConfig wall_scene() {
  MujocoHardwareConfig c;
  c.model_path = std::string(TELEOP_SOURCE_DIR) + "/config/models/scene_wall.xml";
  c.keyframe = "facing_wall";
  c.period_s = 0.001;
  return c;
}

TEST(MujocoHardware, DrivesTheSevenArmJoints) {
  MujocoHardware hw(wall_scene());
  EXPECT_EQ(hw.joints(), 7u);
  EXPECT_STREQ(hw.name(), "mujoco:scene_wall.xml");
  ArmState s;
  ASSERT_EQ(hw.read(s), HardwareStatus::kOk);
  EXPECT_NEAR(s.q_rad[1], -0.2438, 1e-9) << "starts in the keyframe";
}

TEST(MujocoHardware, HoldsItsPoseWithZeroCommandedTorqueBecauseItCompensatesGravity) {
  MujocoHardware hw(wall_scene());
  ArmState start, s;
  ASSERT_EQ(hw.read(start), HardwareStatus::kOk);
  const JointVector zero{};
  for (int i = 0; i < 2000; ++i) ASSERT_EQ(hw.write(zero), HardwareStatus::kOk);  // 2 s
  ASSERT_EQ(hw.read(s), HardwareStatus::kOk);
  for (size_t j = 0; j < 7; ++j) EXPECT_NEAR(s.q_rad[j], start.q_rad[j], 5e-3) << "joint " << j;
}

TEST(MujocoHardware, AnArmWithoutGravityCompensationSagsUnlessItsTorqueCarriesItsWeight) {
  MujocoHardwareConfig config = wall_scene();
  config.gravity_compensated = false;
  MujocoHardware plain(config);
  EXPECT_FALSE(plain.compensates_gravity());
  MujocoHardware compensated(wall_scene());
  ArmState start, s, g;
  ASSERT_EQ(plain.read(start), HardwareStatus::kOk);
  const JointVector zero{};
  for (int i = 0; i < 300; ++i) ASSERT_EQ(plain.write(zero), HardwareStatus::kOk);
  ASSERT_EQ(plain.read(s), HardwareStatus::kOk);
  double moved = 0.0;
  for (size_t j = 0; j < 7; ++j) moved = std::max(moved, std::abs(s.q_rad[j] - start.q_rad[j]));
  EXPECT_GT(moved, 0.05) << "zero torque: it falls";
  // the torque the compensated arm adds itself, commanded to the plain one, holds it
  MujocoHardware carried(config);
  for (int i = 0; i < 300; ++i) {
    ASSERT_EQ(compensated.read(g), HardwareStatus::kOk);
    ASSERT_EQ(compensated.write(zero), HardwareStatus::kOk);
    ASSERT_EQ(carried.write(g.tau_measured_nm), HardwareStatus::kOk);
  }
  ASSERT_EQ(carried.read(s), HardwareStatus::kOk);
  for (size_t j = 0; j < 7; ++j) EXPECT_NEAR(s.q_rad[j], start.q_rad[j], 5e-3) << "joint " << j;
}

TEST(MujocoHardware, PushingIntoTheWallGivesAForceOutOfTheWallThatGrowsWithThePush) {
  // joint 2 (shoulder) forward moves the flange towards the wall at +x
  auto push = [](double torque_nm) {
    MujocoHardware hw(wall_scene());
    JointVector tau{};
    tau[1] = torque_nm;
    ArmState s;
    for (int i = 0; i < 1500; ++i) {
      EXPECT_EQ(hw.write(tau), HardwareStatus::kOk);
    }
    EXPECT_EQ(hw.read(s), HardwareStatus::kOk);
    return s;
  };
  const ArmState soft = push(10.0);
  const ArmState hard = push(30.0);
  EXPECT_LT(soft.force_ext_n[0], -1.0) << "the wall pushes back along -x";
  EXPECT_LT(hard.force_ext_n[0], soft.force_ext_n[0]) << "a harder push, a larger reaction";
  EXPECT_GT(std::abs(hard.tau_ext_nm[1]), 1.0) << "the contact shows in the joint torques";
}

TEST(MujocoHardware, RejectsANonFiniteTorque) {
  MujocoHardware hw(wall_scene());
  JointVector tau{};
  tau[3] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(hw.write(tau), HardwareStatus::kFault);
}

TEST(MujocoHardware, RefusesAPeriodTheTimestepDoesNotDivide) {
  MujocoHardwareConfig c = wall_scene();
  c.period_s = 0.0015;
  const std::string message = test::error_of<std::runtime_error>([&] { MujocoHardware hw(c); });
  EXPECT_NE(message.find("scene_wall.xml"), std::string::npos) << message;
  EXPECT_NE(message.find("does not divide"), std::string::npos) << message;
}

TEST(MujocoHardware, ReadAndWriteDoNotAllocate) {
  MujocoHardware hw(wall_scene());
  ArmState s;
  JointVector tau{};
  tau[1] = 20.0;  // with contacts, the costlier path
  for (int i = 0; i < 100; ++i) ASSERT_EQ(hw.write(tau), HardwareStatus::kOk);
  test::ScopedAllocationCounter counter;
  for (int i = 0; i < 1000; ++i) {
    ASSERT_EQ(hw.write(tau), HardwareStatus::kOk);
    ASSERT_EQ(hw.read(s), HardwareStatus::kOk);
  }
  EXPECT_EQ(counter.count(), 0u);
}

}  // namespace
}  // namespace teleop::robot

namespace teleop::robot {
namespace {

MujocoHardwareConfig two_arm_arm(const std::string& side) {
  MujocoHardwareConfig c;
  c.model_path = std::string(TELEOP_SOURCE_DIR) + "/config/models/dual_arm.xml";
  c.keyframe = "home";
  c.joint_prefix = side + "_";
  c.ee_site = side + "_ee_site";
  return c;
}

TEST(MujocoHardwareOnASharedScene, DrivesEachArmsOwnJointsAndMovesOnlyWhenTheSceneSteps) {
  auto scene = std::make_shared<MujocoScene>(two_arm_arm("left"));
  MujocoHardware left(scene, two_arm_arm("left"));
  MujocoHardware right(scene, two_arm_arm("right"));
  EXPECT_EQ(left.joints(), 7u);
  EXPECT_EQ(right.joints(), 7u);
  EXPECT_STREQ(left.name(), "mujoco:dual_arm.xml:left_*");
  ArmState l0, r0;
  ASSERT_EQ(left.read(l0), HardwareStatus::kOk);
  ASSERT_EQ(right.read(r0), HardwareStatus::kOk);
  EXPECT_NEAR(l0.q_rad[0], -0.066, 1e-9);  // dual_arm's "home": mirrored arms
  EXPECT_NEAR(r0.q_rad[0], 0.066, 1e-9);

  JointVector push{};
  push[0] = 5.0;  // the left arm's first joint only
  ASSERT_EQ(left.write(push), HardwareStatus::kOk);
  ASSERT_EQ(right.write(JointVector{}), HardwareStatus::kOk);
  ArmState l1;
  ASSERT_EQ(left.read(l1), HardwareStatus::kOk);
  EXPECT_EQ(l1.q_rad, l0.q_rad) << "an arm's write leaves the stepping to the scene's owner";
  for (int i = 0; i < 200; ++i) {
    ASSERT_EQ(left.write(push), HardwareStatus::kOk);
    ASSERT_EQ(right.write(JointVector{}), HardwareStatus::kOk);
    scene->step();
  }
  ArmState l2, r2;
  ASSERT_EQ(left.read(l2), HardwareStatus::kOk);
  ASSERT_EQ(right.read(r2), HardwareStatus::kOk);
  EXPECT_GT(l2.q_rad[0] - l0.q_rad[0], 0.01) << "the pushed joint moved";
  for (size_t j = 0; j < 7; ++j) EXPECT_NEAR(r2.q_rad[j], r0.q_rad[j], 2e-3) << "the right arm held, joint " << j;
}

TEST(MujocoHardwareOnASharedScene, NamesTheMissingArmOrSite) {
  auto scene = std::make_shared<MujocoScene>(two_arm_arm("left"));
  MujocoHardwareConfig no_arm = two_arm_arm("middle");
  no_arm.ee_site = "left_ee_site";
  try {
    MujocoHardware hw(scene, no_arm);
    FAIL() << "no joint is named middle_*";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("middle_*"), std::string::npos) << e.what();
  }
  MujocoHardwareConfig no_site = two_arm_arm("left");
  no_site.ee_site = "left_gripper";
  EXPECT_THROW(MujocoHardware(scene, no_site), std::runtime_error);
}

// the fidelity study's "real" robot as the follower's plant (docs/fidelity.md)
MujocoHardwareConfig real_wall_scene(uint64_t seed) {
  MujocoHardwareConfig c = wall_scene();
  c.real_robot = sim::RealRobotSpec{};
  c.real_robot->seed = seed;
  return c;
}

TEST(MujocoHardwareAsARealRobot, IsPerturbedAsDrawnAndReadsNoisySensors) {
  MujocoHardware nominal(wall_scene());
  MujocoHardware real(real_wall_scene(3));
  const mjModel* n = nominal.simulation().model();
  const mjModel* m = real.simulation().model();
  const int link4 = real.simulation().body_id("link4");
  ArmState a, b;
  ASSERT_EQ(real.read(a), HardwareStatus::kOk);
  ASSERT_EQ(real.read(b), HardwareStatus::kOk);
  // the same state read twice: the sensors differ, each within a few sigma of the truth
  for (size_t j = 0; j < 7; ++j) {
    EXPECT_NE(a.q_rad[j], b.q_rad[j]) << "joint " << j;
    EXPECT_NEAR(a.q_rad[j], nominal.simulation().data()->qpos[j], 6e-4) << "joint " << j;
  }
  EXPECT_NE(m->body_mass[link4], n->body_mass[link4]);
  EXPECT_NEAR(m->body_mass[link4], n->body_mass[link4], 0.1 * n->body_mass[link4] + 1e-12);
}

TEST(MujocoHardwareAsARealRobot, ItsOwnGravityCompensationIsTheNominalModelsSoItSagsWhereTheModelHolds) {
  // the nominal arm holds its pose with zero torque (above); the real one is compensated by the
  // model's gravity, which is not its own: it moves, the same way for the same seed
  const auto drift = [](uint64_t seed) {
    MujocoHardware hw(real_wall_scene(seed));
    ArmState start, s;
    EXPECT_EQ(hw.read(start), HardwareStatus::kOk);
    for (int i = 0; i < 500; ++i) EXPECT_EQ(hw.write(JointVector{}), HardwareStatus::kOk);
    EXPECT_EQ(hw.read(s), HardwareStatus::kOk);
    double largest = 0.0;
    for (size_t j = 0; j < 7; ++j) largest = std::max(largest, std::abs(s.q_rad[j] - start.q_rad[j]));
    return largest;
  };
  const double first = drift(5);
  EXPECT_GT(first, 0.02);
  EXPECT_EQ(drift(5), first);
}

TEST(MujocoHardwareAsARealRobot, TheFollowersConfigNamesIt) {
  const ConfigNode section = ConfigNode::load_string(
      "hardware: mujoco\nmujoco:\n  model: " + std::string(TELEOP_SOURCE_DIR) +
          "/config/models/scene_wall.xml\n  real_robot: {seed: 9, perturbation: {mass_fraction: 0.05}}\n",
      "follower.yaml");
  const auto spec = parse_mujoco_hardware(section);
  ASSERT_TRUE(spec->config().real_robot.has_value());
  EXPECT_EQ(spec->config().real_robot->seed, 9u);
  EXPECT_DOUBLE_EQ(spec->config().real_robot->perturbation.mass_fraction, 0.05);
  EXPECT_DOUBLE_EQ(spec->config().real_robot->perturbation.friction_fraction, 0.30);  // the documented default
  EXPECT_FALSE(parse_mujoco_hardware(ConfigNode::load_string("mujoco: {model: " + std::string(TELEOP_SOURCE_DIR) +
                                                                 "/config/models/scene_wall.xml}\n",
                                                             "follower.yaml"))
                   ->config()
                   .real_robot.has_value());
}

}  // namespace
}  // namespace teleop::robot
