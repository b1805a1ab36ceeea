// The hand adapter on a VirtualCanBus against nine emulated drives that turn the MuJoCo hand
// (the in-process twin of the vcan HIL grasp, test/vcan/hand_grasp_vcan_test.cpp): homing finds
// the model's joint limits, the 20 joint angles the adapter reports are the simulation's, the
// fingers stop on an object and hold it against gravity once its support is gone, and each
// fault class leaves the hand in its safe hold with the object still held (a drive fault's
// finger goes limp: the CiA 402 fault reaction switches its power stage off; the others hold).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <string>

#include "hand_plan.h"
#include "hand_rig.h"
#include "teleop/common/config.h"
#include "teleop/hand/grasp_closer.h"
#include "teleop/hand/grasp_object.h"
#include "teleop/hand/mujoco_drive_plants.h"

namespace teleop::hand::test {
namespace {

MujocoDrivePlants load(const std::string& model) {
  // the actuators' limit: the drives' stall torque, 24 V / 4 ohm x 0.01 N m/A x 100 x 0.8
  return MujocoDrivePlants(HandPlant(sim::MujocoModel::load(std::string(TELEOP_SOURCE_DIR) + "/config/models/" + model),
                                     HandCoupling::svh()),
                           4.8);
}

// config/nodes/hand_mujoco.yaml's limits: the model's motor ranges (5 mrad inside)
HandAdapterConfig config_for(const SvhModelIndex& index) {
  HandAdapterConfig c;
  for (size_t k = 0; k < kHandMotors; ++k) {
    c.min_position_rad[k] = 0.0;
    c.max_position_rad[k] = index.motor_max_rad[k] - 0.005;
  }
  return c;
}

double distance(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  return std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
}

TEST(MujocoHandAdapter, HomingFindsTheModelsJointLimits) {
  MujocoDrivePlants plants = load("svh_hand.xml");
  HandAdapterConfig config = config_for(plants.hand().index());
  config.homing.enabled = true;
  config.homing.stop_position_rad.fill(0.0);           // the model's lower limits
  for (auto& c : config.channels) c.offset_rad = 0.3;  // a wrong zero, which homing corrects
  HandRig rig(config, {}, &plants);
  ASSERT_TRUE(rig.run_until(HandPhase::kHoming, 2.0)) << rig.adapter().message();
  ASSERT_TRUE(rig.run_until(HandPhase::kOperational, 6.0)) << rig.adapter().message();
  const HandMotorVector m = plants.hand().motor_positions();
  for (size_t k = 0; k < kHandMotors; ++k) {
    // the adapter's angle is the simulated one: the stop it found is the model's limit (MuJoCo's
    // soft limit gives about 7 mrad under the homing's 0.5 A = 0.4 N m)
    EXPECT_NEAR(rig.adapter().feedback().position_rad[k], m[k], 0.012) << k;
    EXPECT_NEAR(rig.adapter().channel(k).config().offset_rad, 0.0, 0.012) << k;
  }
  // to the upper limits the model has (the middle distal's 1.276: j15's)
  HandTargets t;
  t.enable = true;
  t.position_rad = config.max_position_rad;
  rig.adapter().set_command(t);
  rig.run(1.0);
  for (size_t k = 0; k < kHandMotors; ++k) {
    EXPECT_NEAR(plants.hand().motor_positions()[k], config.max_position_rad[k], 0.02) << k;
  }
  EXPECT_EQ(rig.adapter().phase(), HandPhase::kOperational) << rig.adapter().message();
  EXPECT_EQ(plants.hand().mujoco_warnings(), 0);
}

TEST(MujocoHandAdapter, TheTwentyJointAnglesAreTheSimulations) {
  MujocoDrivePlants plants = load("svh_hand.xml");
  const HandAdapterConfig config = config_for(plants.hand().index());
  HandRig rig(config, {}, &plants);
  ASSERT_TRUE(rig.run_until(HandPhase::kOperational, 2.0)) << rig.adapter().message();
  HandTargets t;
  t.enable = true;
  for (size_t k = 0; k < kHandMotors; ++k) t.position_rad[k] = 0.6 * config.max_position_rad[k];
  rig.adapter().set_command(t);
  rig.run(1.0);
  const HandJointVector reported = rig.adapter().joint_positions();
  const HandJointVector simulated = plants.hand().joint_positions();
  for (size_t j = 0; j < kHandJoints; ++j) {
    // encoder ticks (15 urad) and the coupling's compliance (< 1 mrad)
    EXPECT_NEAR(reported[j], simulated[j], 1e-3) << kHandJointNames[j];
    EXPECT_GT(std::abs(simulated[j]), 0.1) << kHandJointNames[j];  // the hand moved
  }
}

// the hand closed around the object, its support released, settled
struct Grasped {
  MujocoDrivePlants plants = load("svh_hand_grasp.xml");
  HandRig rig{config_for(plants.hand().index()), {}, &plants};
  GraspObject object{plants.hand()};
  GraspCloser closer{power_grasp(rig.adapter().config().max_position_rad)};
  HandTargets targets;

  void close_and_release() {
    ASSERT_TRUE(rig.run_until(HandPhase::kOperational, 2.0)) << rig.adapter().message();
    targets.enable = true;  // open first (as the vcan test, whose drives start late)
    rig.adapter().set_command(targets);
    rig.run(0.6);
    closer.start(rig.adapter().feedback().position_rad);
    targets.current_limit_a = closer.config().current_limit_a;
    grasp_s = 0.0;
    hold(3.0);
    object.release();
    hold(1.0);
  }
  /// The grasp controller keeps running: the fingers that touch keep pressing.
  void hold(double seconds) {
    for (double end = grasp_s + seconds; grasp_s < end; grasp_s += rig.period_s()) {
      targets.position_rad = closer.update(grasp_s, rig.adapter().feedback().position_rad);
      rig.adapter().set_command(targets);
      rig.cycle();
    }
  }
  double grasp_s = 0.0;
};

TEST(MujocoHandAdapter, FingersStopOnTheObjectAndTheGraspHoldsItAgainstGravity) {
  Grasped g;
  const auto supported_at = g.object.position_m();
  ASSERT_NO_FATAL_FAILURE(g.close_and_release());
  // the fingers were stopped by the object, not by their limits
  int stopped = 0;
  for (size_t k = 0; k < kHandMotors; ++k) {
    if (!g.closer.in_contact(k)) continue;
    ++stopped;
    EXPECT_LT(g.closer.contact_rad(k), g.rig.adapter().config().max_position_rad[k] - 0.1) << k;
  }
  EXPECT_GE(stopped, 5);
  const auto settled = g.object.position_m();
  EXPECT_LT(distance(settled, supported_at), 0.04);  // it settled into the grip (25 mm)
  g.hold(5.0);
  const auto held = g.object.position_m();
  std::printf(
      "grasp: %d motors stopped by contact, object settled %.1f mm, then moved %.3f mm in 5 s; %d links "
      "touch it, %.1f N\n",
      stopped, distance(settled, supported_at) * 1e3, distance(held, settled) * 1e3, g.object.touching_links(),
      g.object.hand_contact_force_n());
  std::printf("motors: target / measured [rad] / current [A]:");
  for (size_t k = 0; k < kHandMotors; ++k) {
    std::printf(" %.3f/%.3f/%.2f", g.closer.targets()[k], g.rig.adapter().feedback().position_rad[k],
                g.rig.adapter().feedback().current_a[k]);
  }
  std::printf("\n");
  EXPECT_LT(distance(held, settled), 1e-3);
  EXPECT_GE(g.object.touching_links(), 5);
  EXPECT_EQ(g.rig.adapter().phase(), HandPhase::kOperational) << g.rig.adapter().message();
  EXPECT_EQ(g.plants.hand().mujoco_warnings(), 0);
  // what the adapter reports is what the simulation holds: the motors' main joints to the
  // encoder's tick; the coupled joints, which the adapter computes through the coupling table,
  // within the mechanism's compliance under the grip's load (the equalities' softness: up to
  // 26 mrad at the middle fingertip pressed on the object, against < 1 mrad moving freely)
  const HandJointVector reported = g.rig.adapter().joint_positions();
  const HandJointVector simulated = g.plants.hand().joint_positions();
  for (size_t j = 0; j < kHandJoints; ++j) {
    const bool main = g.plants.hand().index().equality[j] < 0;
    EXPECT_NEAR(reported[j], simulated[j], main ? 1e-4 : 0.035) << kHandJointNames[j];
  }
}

// One fault during the grasp: safe hold, and the object stays in the hand (3 s).
struct FaultInGrasp {
  const char* name;
  uint32_t bit;
  size_t motor;
  std::function<void(Grasped&)> inject;
};

void fault_in_grasp(const FaultInGrasp& f) {
  Grasped g;
  ASSERT_NO_FATAL_FAILURE(g.close_and_release());
  const auto before = g.object.position_m();
  f.inject(g);
  g.hold(0.5);  // the operator does not know yet (and in safe hold the adapter ignores commands)
  ASSERT_TRUE(g.rig.run_until(HandPhase::kSafeHold, 1.5)) << f.name;
  EXPECT_NE(g.rig.adapter().feedback().faults[f.motor] & f.bit, 0u) << f.name << ": " << g.rig.adapter().message();
  g.rig.run(3.0);
  const double moved = distance(g.object.position_m(), before);
  std::printf("%s: %s; object moved %.2f mm, %d links touch it\n", f.name, g.rig.adapter().message(), moved * 1e3,
              g.object.touching_links());
  EXPECT_LT(moved, 3e-3) << f.name;
  EXPECT_GE(g.object.touching_links(), 4) << f.name;
  EXPECT_EQ(g.rig.adapter().phase(), HandPhase::kSafeHold) << f.name;
}

TEST(MujocoHandAdapter, SafeHoldKeepsTheObjectOnAMissingHeartbeat) {
  fault_in_grasp(
      {"heartbeat", hand_fault::kHeartbeat, 3, [](Grasped& g) { g.rig.drive(3).set_heartbeat_suppressed(true); }});
}

TEST(MujocoHandAdapter, SafeHoldKeepsTheObjectOnStalePdos) {
  fault_in_grasp({"stale pdo", hand_fault::kStalePdo, 5,
                  [](Grasped& g) { g.rig.drive(5).drop_tpdos(drive::EmulatedDrive::kDropForever); }});
}

TEST(MujocoHandAdapter, SafeHoldKeepsTheObjectOnBusOff) {
  fault_in_grasp({"bus-off", hand_fault::kBusOff, 0,
                  [](Grasped& g) { g.rig.adapter_endpoint().set_state(CanBusState::kBusOff); }});
}

TEST(MujocoHandAdapter, SafeHoldKeepsTheObjectOnAnSdoAbort) {
  // the operator lowers node 3's current limit, which goes out by SDO: node 3 refuses it
  fault_in_grasp({"sdo abort", hand_fault::kSdo, 2, [](Grasped& g) {
                    g.rig.drive(2).set_sdo_refused(true);
                    g.targets.current_limit_a[2] = 0.7;
                  }});
}

TEST(MujocoHandAdapter, ADriveFaultLetsItsFingerGoLimpTheOthersHold) {
  // the ring finger's drive in fault: its power stage off, the finger limp; the thumb and the
  // other fingers, quick-stopped, keep the object
  fault_in_grasp({"emcy", hand_fault::kEmcy, 6, [](Grasped& g) { g.rig.drive(6).raise_fault(emcy::kOverCurrent); }});
}

// item 5: the operator's grasp as the leader sends it (config/nodes/leader_hand.yaml, an open-loop
// HandCommand plan) grasps the tube too, and holds it after the support goes
TEST(MujocoHandAdapter, TheLeadersHandPlanGraspsTheTube) {
  const ConfigNode root = ConfigNode::load_file(std::string(TELEOP_SOURCE_DIR) + "/config/nodes/leader_hand.yaml");
  const leader::HandPlan plan = leader::parse_hand_plan(root.child("leader").child("hand"));
  MujocoDrivePlants plants = load("svh_hand_grasp.xml");
  HandRig rig(config_for(plants.hand().index()), {}, &plants);
  GraspObject object(plants.hand());
  ASSERT_TRUE(rig.run_until(HandPhase::kOperational, 2.0)) << rig.adapter().message();
  HandTargets t;
  t.enable = true;
  double time_s = 0.0;
  const auto play = [&](double until_s) {
    for (; time_s < until_s; time_s += rig.period_s()) {
      plan.sample(time_s, t.position_rad, t.current_limit_a);
      rig.adapter().set_command(t);
      rig.cycle();
    }
  };
  play(5.0);
  EXPECT_GE(object.touching_links(), 5);
  object.release();
  play(6.0);
  const auto settled = object.position_m();
  play(11.0);
  std::printf("the leader's plan: the tube moved %.3f mm in 5 s after settling, %d links\n",
              distance(object.position_m(), settled) * 1e3, object.touching_links());
  EXPECT_LT(distance(object.position_m(), settled), 1e-3);
  EXPECT_GE(object.touching_links(), 5);
  EXPECT_EQ(rig.adapter().phase(), HandPhase::kOperational) << rig.adapter().message();
}

}  // namespace
}  // namespace teleop::hand::test
