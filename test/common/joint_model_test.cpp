#include "teleop/common/joint_model.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace teleop {
namespace {

JointModelParams free_params(size_t joints = 2) {
  JointModelParams p;
  p.joints = joints;
  p.inertia_kgm2 = 0.2;
  p.viscous_nms_per_rad = 0.0;
  p.wall_q_rad = 1e9;  // no wall
  return p;
}

TEST(JointModel, RejectsBadParametersWhenConstructed) {
  JointModelParams p = free_params();
  p.joints = 0;
  EXPECT_THROW(JointModel{p}, std::invalid_argument);
  p.joints = kMaxJoints + 1;
  EXPECT_THROW(JointModel{p}, std::invalid_argument);
  p = free_params();
  p.inertia_kgm2 = 0.0;
  EXPECT_THROW(JointModel{p}, std::invalid_argument);
  p.inertia_kgm2 = -1.0;
  EXPECT_THROW(JointModel{p}, std::invalid_argument);
}

TEST(JointModel, ResetSetsPoseAndZeroVelocity) {
  JointModel m(free_params(3));
  JointVector q{};
  q[0] = 0.1;
  q[1] = -0.2;
  q[2] = 0.3;
  m.reset(q);
  EXPECT_EQ(m.joints(), 3u);
  EXPECT_DOUBLE_EQ(m.q()[0], 0.1);
  EXPECT_DOUBLE_EQ(m.q()[1], -0.2);
  EXPECT_DOUBLE_EQ(m.q()[2], 0.3);
  for (size_t i = 0; i < 3; ++i) EXPECT_EQ(m.dq()[i], 0.0);
}

TEST(JointModel, AcceleratesAsTorqueOverInertiaWhenFreeUnderConstantTorque) {
  const JointModelParams p = free_params();
  JointModel m(p);
  m.reset(JointVector{});
  JointVector tau{};
  tau[0] = 0.5;   // expected acceleration 2.5 rad/s^2
  tau[1] = -0.1;  // -0.5 rad/s^2
  const double dt = 0.001;
  const int steps = 1000;
  double previous_dq0 = 0.0;
  for (int k = 0; k < steps; ++k) {
    m.step(tau, dt);
    EXPECT_NEAR((m.dq()[0] - previous_dq0) / dt, tau[0] / p.inertia_kgm2, 1e-9);
    previous_dq0 = m.dq()[0];
  }
  const double t = steps * dt;
  EXPECT_NEAR(m.dq()[0], 2.5 * t, 1e-9);
  EXPECT_NEAR(m.dq()[1], -0.5 * t, 1e-9);
  // q = a t^2 / 2, to within the semi-implicit Euler error a t dt / 2
  EXPECT_NEAR(m.q()[0], 0.5 * 2.5 * t * t, 2.5 * t * dt);
  EXPECT_NEAR(m.q()[1], -0.5 * 0.5 * t * t, 0.5 * t * dt);
  // no wall, no contact
  EXPECT_EQ(m.contact_torque()[0], 0.0);
}

TEST(JointModel, LeavesJointsBeyondCountUntouchedWhenStepping) {
  JointModel m(free_params(1));
  m.reset(JointVector{});
  JointVector tau{};
  tau[0] = 1.0;
  tau[1] = 1.0;  // joint 1 does not exist in this model
  m.step(tau, 0.01);
  EXPECT_GT(m.dq()[0], 0.0);
  EXPECT_EQ(m.dq()[1], 0.0);
  EXPECT_EQ(m.q()[1], 0.0);
}

TEST(JointModel, WallExertsNoTorqueWhenNotPenetrated) {
  JointModelParams p = free_params();
  p.wall_q_rad = 0.5;
  p.wall_stiffness_nm_per_rad = 2000.0;
  JointModel m(p);
  JointVector q{};
  q[0] = 0.4;
  m.reset(q);
  EXPECT_EQ(m.contact_torque()[0], 0.0);
  q[0] = 0.5;  // touching, not penetrating
  m.reset(q);
  EXPECT_EQ(m.contact_torque()[0], 0.0);
}

TEST(JointModel, WallPushesBackProportionallyWhenPenetrated) {
  JointModelParams p = free_params();
  p.wall_q_rad = 0.5;
  p.wall_stiffness_nm_per_rad = 2000.0;
  JointModel m(p);
  JointVector q{};
  q[0] = 0.6;
  q[1] = 0.6;  // the wall is on joint 0 only
  m.reset(q);
  EXPECT_NEAR(m.contact_torque()[0], -2000.0 * 0.1, 1e-9);
  EXPECT_EQ(m.contact_torque()[1], 0.0);
  m.step(JointVector{}, 0.001);
  EXPECT_LT(m.dq()[0], 0.0);  // pushed back out
  EXPECT_EQ(m.dq()[1], 0.0);
}

TEST(JointModel, SettlesAtForceBalanceWhenPushedIntoWall) {
  JointModelParams p = free_params(1);
  p.wall_q_rad = 0.2;
  p.wall_stiffness_nm_per_rad = 1000.0;
  p.viscous_nms_per_rad = 5.0;  // damped so that it settles
  JointModel m(p);
  m.reset(JointVector{});
  JointVector tau{};
  tau[0] = 2.0;
  bool touched = false;
  for (int k = 0; k < 20'000; ++k) {
    const bool inside = m.q()[0] > p.wall_q_rad;
    // contact only while penetrated, and always pushing back
    if (inside) {
      touched = true;
      EXPECT_LT(m.contact_torque()[0], 0.0);
    } else {
      EXPECT_EQ(m.contact_torque()[0], 0.0);
    }
    m.step(tau, 0.0005);
  }
  EXPECT_TRUE(touched);
  // the wall balances the applied torque: penetration tau / k
  EXPECT_NEAR(m.q()[0], p.wall_q_rad + tau[0] / p.wall_stiffness_nm_per_rad, 1e-6);
  EXPECT_NEAR(m.contact_torque()[0], -tau[0], 1e-3);
}

TEST(JointModel, VelocityDecaysExponentiallyUnderViscousFriction) {
  JointModelParams p = free_params(1);
  p.inertia_kgm2 = 0.2;
  p.viscous_nms_per_rad = 0.5;  // time constant I / b = 0.4 s
  JointModel m(p);
  m.reset(JointVector{});
  const double dt = 0.0001;
  JointVector kick{};
  kick[0] = 100.0;
  m.step(kick, dt);  // one impulse: dq = 100 * dt / I = 0.05
  const double v0 = m.dq()[0];
  ASSERT_NEAR(v0, 0.05, 1e-12);
  const double q0 = m.q()[0];
  const JointVector none{};
  const int steps = 4000;  // 0.4 s = one time constant
  double previous = v0;
  for (int k = 0; k < steps; ++k) {
    m.step(none, dt);
    ASSERT_GT(m.dq()[0], 0.0);
    ASSERT_LT(m.dq()[0], previous);  // monotonic decay, never reverses
    previous = m.dq()[0];
  }
  EXPECT_NEAR(m.dq()[0] / v0, std::exp(-1.0), 1e-3);
  // the distance travelled tends to v0 * tau (here after one time constant: v0 tau (1 - 1/e))
  EXPECT_NEAR(m.q()[0] - q0, v0 * 0.4 * (1.0 - std::exp(-1.0)), 1e-4 * v0);
}

}  // namespace
}  // namespace teleop

namespace teleop {
namespace {

TEST(JointModel, PutsTheWallOnTheConfiguredJointOnly) {
  JointModelParams p;
  p.joints = 3;
  p.wall_joint = 2;
  p.wall_q_rad = 0.1;
  JointModel m(p);
  JointVector q{};
  q[0] = 0.5;  // past the wall angle, but joint 0 has no wall
  q[2] = 0.15;
  m.reset(q);
  EXPECT_EQ(m.contact_torque()[0], 0.0);
  EXPECT_NEAR(m.contact_torque()[2], -p.wall_stiffness_nm_per_rad * 0.05, 1e-9);
  p.wall_joint = 3;
  EXPECT_THROW(JointModel{p}, std::invalid_argument);
}

}  // namespace
}  // namespace teleop
