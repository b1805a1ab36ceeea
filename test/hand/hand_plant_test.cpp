// The SVH-class hand as a MuJoCo plant driven by the paper's position control: the mechanism
// (the model's equalities) keeps every coupled joint on its motor through a full close and open.
#include "teleop/hand/hand_plant.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "allocation_counter.h"
#include "teleop/control/min_jerk.h"
#include "teleop/hand/position_control.h"

namespace teleop::hand {
namespace {

HandPlant load_hand() {
  return HandPlant(sim::MujocoModel::load(std::string(TELEOP_SOURCE_DIR) + "/config/models/svh_hand.xml"),
                   HandCoupling::svh());
}

// Drives every motor from open to 95 % of its range and back (min-jerk, 0.6 s each way, 0.2 s
// holds) and returns the worst coupling residual seen after any step; `plant` ends open.
struct CloseOpen {
  double worst_residual_rad = 0.0;
  double worst_closed_error_rad = 0.0;  // |m - target| of any motor after the closed hold
  double closed_residual_rad = 0.0;     // the coupling residual after the closed hold
  int warnings = 0;
};
CloseOpen close_and_open(HandPlant& plant, CouplingMode mode) {
  plant.mujoco().reset("open");
  const HandPositionControl control(plant, mode, 40.0, 1.0);
  std::vector<double> open(kHandMotors, 0.0);
  std::vector<double> closed(kHandMotors);
  for (size_t k = 0; k < kHandMotors; ++k) closed[k] = 0.95 * plant.index().motor_max_rad[k];
  const double dt = plant.model()->opt.timestep;
  CloseOpen result;
  HandMotorVector m_ref{};
  HandMotorVector dm_ref{};
  for (const auto& [from, to] : {std::pair{open, closed}, std::pair{closed, open}}) {
    const control::MinJerkMotion motion(from, to, 0.6);
    for (double t = 0.0; t < 0.8; t += dt) {
      motion.sample(t, m_ref, dm_ref);
      plant.begin_step();
      control.apply(plant, m_ref, dm_ref);
      plant.end_step();
      result.worst_residual_rad = std::max(result.worst_residual_rad, plant.coupling_residual_rad());
    }
    if (to == closed) {
      result.closed_residual_rad = plant.coupling_residual_rad();
      const HandMotorVector m = plant.motor_positions();
      for (size_t k = 0; k < kHandMotors; ++k) {
        result.worst_closed_error_rad = std::max(result.worst_closed_error_rad, std::abs(m[k] - closed[k]));
      }
    }
  }
  result.warnings = plant.mujoco_warnings();
  return result;
}

TEST(HandPlant, CouplingsHoldWithinAMilliradianOverAFullCloseAndOpen) {
  HandPlant plant = load_hand();
  const CloseOpen run = close_and_open(plant, CouplingMode::kConstraint);
  EXPECT_LT(run.worst_residual_rad, 1e-3) << "worst coupling residual [rad]";
  std::printf("close/open with the equalities: worst coupling residual %.3g rad\n", run.worst_residual_rad);
  // the fingers did close: every motor within 20 mrad of 95 % of its range (gravity on a PD)
  EXPECT_LT(run.worst_closed_error_rad, 0.02);
  EXPECT_EQ(run.warnings, 0);
  // and opened again
  for (const double m : plant.motor_positions()) EXPECT_NEAR(m, 0.0, 0.02);
}

TEST(HandPlant, WithoutTheEqualitiesTheCoupledJointsServoToTheirCoupledReference) {
  HandPlant plant = load_hand();
  const CloseOpen run = close_and_open(plant, CouplingMode::kServo);
  EXPECT_FALSE(plant.couplings_active());
  // a PD per coupled joint (Gazebo's mimic-joint plugin can couple joints this way, with a PID)
  // holds the coupled pose once the motors rest
  // closed, the servos sit on the coupled reference while the motors' own joints sag under gravity
  // by up to 20 mrad (a PD without gravity compensation, as the paper's): the residual is that sag
  // times the coupling factor (at most 1.45)
  EXPECT_LT(run.closed_residual_rad, 1.45 * 0.02);
  // while the fingers move, the servos lag behind their motor's joint (no acceleration feed-
  // forward) far more than the mechanism lets its joints: tens of mrad against under one
  EXPECT_LT(run.worst_residual_rad, 0.15);
  std::printf("close/open with servos: worst coupling residual %.3g rad, %.3g rad when closed\n",
              run.worst_residual_rad, run.closed_residual_rad);
  EXPECT_LT(run.worst_closed_error_rad, 0.02);
  EXPECT_EQ(run.warnings, 0);
}

TEST(HandPlant, LinkInertiaSettingReplacesTheInertiaOfEveryMovingHandBody) {
  HandPlant plant = load_hand();
  const double own = plant.channel_inertia_kgm2(hand_motor::kRing, true);
  plant.set_link_inertia(0.01);
  for (const int id : plant.index().joint_id) {
    const mjtNum* inertia = plant.model()->body_inertia + 3 * plant.model()->jnt_bodyid[id];
    EXPECT_EQ(inertia[0], 0.01);
    EXPECT_EQ(inertia[2], 0.01);
  }
  plant.mujoco().reset("open");
  // the ring motor moves three links: at least 1 + 1.3588^2 + 1.42093^2 times 0.01 through them
  const double through = plant.channel_inertia_kgm2(hand_motor::kRing, true);
  EXPECT_GT(through, 0.01 * (1 + 1.3588 * 1.3588 + 1.42093 * 1.42093));
  EXPECT_GT(through, 100 * own);
  EXPECT_LT(plant.channel_inertia_kgm2(hand_motor::kRing, false), through);
  EXPECT_THROW(plant.set_link_inertia(0.0), std::invalid_argument);
}

TEST(HandPlant, MotorPositionsAreTheMainJointsAndTheTorqueLimitTheActuators) {
  HandPlant plant = load_hand();
  plant.data()->qpos[plant.index().qpos[main_joint_of(hand_motor::kPinky)]] = 0.3;
  EXPECT_DOUBLE_EQ(plant.motor_positions()[hand_motor::kPinky], 0.3);
  EXPECT_DOUBLE_EQ(plant.motor_torque_limit_nm(hand_motor::kPinky), 1.2);
  plant.set_motor_torque(hand_motor::kPinky, 0.5);
  EXPECT_EQ(plant.data()->ctrl[plant.index().actuator[hand_motor::kPinky]], 0.5);
}

TEST(HandPlant, AControlCycleDoesNotAllocate) {
  for (const CouplingMode mode : {CouplingMode::kConstraint, CouplingMode::kServo}) {
    HandPlant plant = load_hand();
    plant.mujoco().reset("open");
    const HandPositionControl control(plant, mode, 40.0, 1.0);
    const control::MinJerkMotion motion(std::vector<double>(kHandMotors, 0.0), std::vector<double>(kHandMotors, 0.3), 0.1);
    HandMotorVector m_ref{};
    HandMotorVector dm_ref{};
    double sink = 0.0;
    const test::ScopedAllocationCounter allocations;
    for (int k = 0; k < 100; ++k) {
      motion.sample(k * 1e-3, m_ref, dm_ref);
      plant.begin_step();
      control.apply(plant, m_ref, dm_ref);
      plant.end_step();
      sink += plant.motor_positions()[0] + plant.coupling_residual_rad() + plant.tip_force_n();
    }
    EXPECT_EQ(allocations.count(), 0u);
    EXPECT_TRUE(std::isfinite(sink));
  }
}

}  // namespace
}  // namespace teleop::hand
