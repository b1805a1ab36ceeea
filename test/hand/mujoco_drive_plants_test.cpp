// The MuJoCo hand as the drives' plant, without CAN: a constant motor torque moves its channel
// until the model's joint limit stops it, the coupled joints stay on their motor, a finger
// pressed onto an object stops on it, a jammed channel holds, a step does not allocate.
#include "teleop/hand/mujoco_drive_plants.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "allocation_counter.h"
#include "teleop/hand/grasp_object.h"

namespace teleop::hand {
namespace {

constexpr double kSubstepS = 50e-6;  // the drives' current-loop period

MujocoDrivePlants load(const std::string& model) {
  return MujocoDrivePlants(HandPlant(sim::MujocoModel::load(std::string(TELEOP_SOURCE_DIR) + "/config/models/" + model),
                                     HandCoupling::svh()),
                           4.8);
}

// `torques` on every channel for `seconds`, applied in the drives' substeps between the plant's
// steps, as the emulated drives do; returns the worst coupling residual after any step
double run(MujocoDrivePlants& plants, const HandMotorVector& torques_nm, double seconds, bool jammed = false) {
  double worst = 0.0;
  const auto steps = static_cast<int>(std::lround(seconds / plants.step_s()));
  const auto substeps = static_cast<int>(std::lround(plants.step_s() / kSubstepS));
  for (int i = 0; i < steps; ++i) {
    for (int s = 0; s < substeps; ++s) {
      for (size_t k = 0; k < kHandMotors; ++k) plants.channel(k).apply(torques_nm[k], kSubstepS, jammed);
    }
    plants.step();
    worst = std::max(worst, plants.hand().coupling_residual_rad());
  }
  return worst;
}

HandMotorVector only(size_t motor, double torque_nm) {
  HandMotorVector t{};
  t[motor] = torque_nm;
  return t;
}

TEST(MujocoDrivePlants, ConstantMotorTorqueMovesItsChannelUntilTheJointLimitStopsIt) {
  // where gravity alone takes the hand (fingers up: the thumb falls open sideways)
  MujocoDrivePlants idle = load("svh_hand.xml");
  run(idle, HandMotorVector{}, 1.05);
  MujocoDrivePlants plants = load("svh_hand.xml");
  const size_t k = hand_motor::kRing;                           // one motor for the whole finger
  const double limit = plants.hand().index().motor_max_rad[k];  // 0.98175 (the URDF's)
  EXPECT_EQ(plants.step_s(), 1e-3);
  EXPECT_NEAR(plants.channel(k).position_rad(), 0.0, 1e-12);

  run(plants, only(k, 0.3), 0.05);
  EXPECT_GT(plants.channel(k).position_rad(), 0.05);  // it moves
  EXPECT_GT(plants.channel(k).velocity_radps(), 1.0);
  run(plants, only(k, 0.3), 1.0);
  // at rest on the model's limit (MuJoCo's soft limit yields a little under 0.3 N m)
  EXPECT_NEAR(plants.channel(k).position_rad(), limit, 0.02);
  EXPECT_LT(std::abs(plants.channel(k).velocity_radps()), 1e-3);
  EXPECT_NEAR(plants.hand().motor_positions()[k], plants.channel(k).position_rad(), 1e-12);
  EXPECT_DOUBLE_EQ(plants.last_torque_nm()[k], 0.3);
  // the other channels went where gravity alone takes them
  for (size_t other = 0; other < kHandMotors; ++other) {
    if (other == k) continue;
    EXPECT_NEAR(plants.channel(other).position_rad(), idle.channel(other).position_rad(), 0.01) << other;
  }

  // and back: the lower limit, 0
  run(plants, only(k, -0.3), 1.0);
  EXPECT_NEAR(plants.channel(k).position_rad(), 0.0, 0.02);
  EXPECT_EQ(plants.hand().mujoco_warnings(), 0);
}

TEST(MujocoDrivePlants, BetweenStepsAChannelReadsItsStateExtrapolated) {
  MujocoDrivePlants plants = load("svh_hand.xml");
  const size_t k = hand_motor::kRing;
  run(plants, only(k, 0.2), 0.02);
  const double m = plants.channel(k).position_rad();
  const double dm = plants.channel(k).velocity_radps();
  ASSERT_GT(dm, 0.1);
  plants.channel(k).apply(0.2, 4e-4, false);
  EXPECT_NEAR(plants.channel(k).position_rad(), m + dm * 4e-4, 1e-12);
  EXPECT_EQ(plants.channel(k).velocity_radps(), dm);
}

TEST(MujocoDrivePlants, CouplingsHoldWhileTheDrivesCloseAndOpenTheHand) {
  // every channel driven by a position loop as a drive's (a PD on the channel's own reading,
  // 40 rad/s on its ~1e-3 kg m^2, within the drives' 1.2 N m) on a reference that moves at the
  // drives' 3 rad/s reference limit, to 90 % of its range and back
  MujocoDrivePlants plants = load("svh_hand.xml");
  const SvhModelIndex& index = plants.hand().index();
  double worst = 0.0;
  HandMotorVector ref{};
  for (const double fraction : {0.9, 0.0}) {
    for (int ms = 0; ms < 800; ++ms) {
      HandMotorVector t{};
      for (size_t k = 0; k < kHandMotors; ++k) {
        ref[k] += std::clamp(fraction * index.motor_max_rad[k] - ref[k], -3e-3, 3e-3);
        const double error = ref[k] - plants.channel(k).position_rad();
        t[k] = std::clamp(1.6 * error - 0.08 * plants.channel(k).velocity_radps(), -1.2, 1.2);
      }
      worst = std::max(worst, run(plants, t, 1e-3));
    }
    for (size_t k = 0; k < kHandMotors; ++k) {
      EXPECT_NEAR(plants.channel(k).position_rad(), fraction * index.motor_max_rad[k], 0.03) << k;
    }
  }
  std::printf("worst coupling residual over the close/open: %.2e rad\n", worst);
  RecordProperty("worst_coupling_residual_rad", std::to_string(worst));
  EXPECT_LT(worst, 1e-3);
  EXPECT_EQ(plants.hand().mujoco_warnings(), 0);
}

TEST(MujocoDrivePlants, AFingerPressedOntoAnObjectStopsOnIt) {
  // the grasp scene's object (held by its support) lies in the index finger's way
  MujocoDrivePlants plants = load("svh_hand_grasp.xml");
  GraspObject object(plants.hand());
  ASSERT_TRUE(object.supported());
  EXPECT_EQ(object.hand_contacts(), 0);
  const size_t k = hand_motor::kIndexProximal;
  run(plants, only(k, 0.3), 1.0);
  const double stopped = plants.channel(k).position_rad();
  EXPECT_GT(stopped, 0.05);                                          // it moved
  EXPECT_LT(stopped, plants.hand().index().motor_max_rad[k] - 0.3);  // but the object stopped it
  // at rest on it (the support, a soft weld, gives a little: mrad/s)
  EXPECT_LT(std::abs(plants.channel(k).velocity_radps()), 0.02);
  EXPECT_GT(object.hand_contacts(), 0);
  EXPECT_GT(object.hand_contact_force_n(), 1.0);
  EXPECT_EQ(plants.hand().mujoco_warnings(), 0);
}

TEST(MujocoDrivePlants, AJammedChannelHoldsWhereTheJamFoundIt) {
  MujocoDrivePlants plants = load("svh_hand.xml");
  const size_t k = hand_motor::kMiddleProximal;
  run(plants, only(k, 0.2), 0.1);
  const double at = plants.channel(k).position_rad();
  ASSERT_GT(at, 0.1);
  run(plants, only(k, 0.2), 0.5, true);
  EXPECT_NEAR(plants.channel(k).position_rad(), at, 1e-6);
  EXPECT_EQ(plants.channel(k).velocity_radps(), 0.0);
  run(plants, only(k, 0.2), 0.1);  // free again
  EXPECT_GT(plants.channel(k).position_rad(), at + 0.05);
}

TEST(MujocoDrivePlants, StepAndApplyDoNotAllocate) {
  MujocoDrivePlants plants = load("svh_hand_grasp.xml");
  HandMotorVector t{};
  t.fill(0.2);
  run(plants, t, 0.01);
  const test::ScopedAllocationCounter counter;
  run(plants, t, 0.05);
  run(plants, t, 0.01, true);
  EXPECT_EQ(counter.count(), 0u);
}

TEST(MujocoDrivePlants, RefusesATorqueLimitThatIsNotPositive) {
  auto hand = [] {
    return HandPlant(sim::MujocoModel::load(std::string(TELEOP_SOURCE_DIR) + "/config/models/svh_hand.xml"),
                     HandCoupling::svh());
  };
  EXPECT_THROW(MujocoDrivePlants(hand(), 0.0), std::invalid_argument);
  EXPECT_THROW(MujocoDrivePlants(hand(), std::nan("")), std::invalid_argument);
  const MujocoDrivePlants plants(hand(), 4.8);
  EXPECT_EQ(plants.hand().motor_torque_limit_nm(0), 4.8);
}

}  // namespace
}  // namespace teleop::hand
