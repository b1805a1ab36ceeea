// The follower's end of the TDPA channel (follower/passive_reference.h): the passivity
// controller's drift in the Cartesian reference, its return in free motion only, and a session
// reset that leaves the reference where it is.
#include "teleop/follower/passive_reference.h"

#include <gtest/gtest.h>

#include <cmath>

#include "node_harness.h"

namespace teleop::follower {
namespace {

constexpr double kCycleS = 0.001;

class PassiveReferenceTest : public ::testing::Test {
 protected:
  transport::Participant participant{test::test_participant_config("follower")};
  // no leader: the observed energy stays 0, so every outflow at this port is a deficit
  runtime::TdpaLink link{participant, "follower", "", runtime::TdpaEnd::kFollower, 6, kCycleS, true, 1e9};
  PassiveReference reference{link, kCycleS, settings()};
  ValidCommand command;
  ValidCommand corrected;

  static runtime::TdpaSettings settings() {
    runtime::TdpaSettings s;
    s.drift_time_constant_s = 0.5;
    s.drift_max_speed_m_per_s = 0.05;
    s.drift_contact_force_n = 3.0;
    return s;
  }

  PassiveReferenceTest() {
    command.mode = msg::CONTROL_CARTESIAN_IMPEDANCE;
    command.x_des_m = {0.5, 0.0, 0.6};
  }

  // `cycles` with the command moving +x at `v` while the environment pushes with `f_x`
  void run(int cycles, double v, double f_x) {
    control::Vector6 wrench = control::Vector6::Zero();
    wrench[0] = f_x;
    command.twist_des[0] = v;
    for (int k = 0; k < cycles; ++k) reference.apply(command, wrench, corrected);
  }
};

TEST_F(PassiveReferenceTest, HoldsBackAMotionAgainstTheEnvironmentAsDrift) {
  // moving +x into a push of -5 N takes energy the channel has not got: the controller stops it
  run(100, 0.1, -5.0);
  EXPECT_EQ(corrected.twist_des[0], 0.0);
  EXPECT_NEAR(reference.position_drift_m(), 0.01, 1e-9);  // 100 cycles of 0.1 m/s held back
  EXPECT_NEAR(corrected.x_des_m[0], 0.5 - 0.01, 1e-9);
}

TEST_F(PassiveReferenceTest, KeepsTheDriftWhileInContactAndReturnsItInFreeMotion) {
  run(100, 0.1, -5.0);
  // at rest against the environment (5 N > 3 N): returning (+x) would press into it, the drift waits
  run(500, 0.0, -5.0);
  EXPECT_NEAR(reference.position_drift_m(), 0.01, 1e-9);
  // free (no push): the request passes without energy (f v = 0) and the drift comes back
  run(500, 0.0, 0.0);  // one time constant
  EXPECT_NEAR(reference.position_drift_m(), 0.01 * std::exp(-1.0), 2e-4);
}

TEST_F(PassiveReferenceTest, ASessionResetLeavesTheReferenceWhereItIs) {
  run(100, 0.1, -5.0);
  const double before = corrected.x_des_m[0];
  reference.reset();
  run(1, 0.0, -5.0);
  EXPECT_NEAR(corrected.x_des_m[0], before, 1e-9) << "no step of the drift's size into the environment";
  EXPECT_NEAR(reference.position_drift_m(), 0.01, 1e-9);
}

}  // namespace
}  // namespace teleop::follower
