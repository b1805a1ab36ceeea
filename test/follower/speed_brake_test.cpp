#include "teleop/follower/speed_brake.h"

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <Eigen/Dense>
#include <memory>
#include <string>

#include "teleop/control/arm_dynamics.h"

namespace teleop::follower {
namespace {

constexpr double kCycleS = 1e-3;
constexpr double kShare = 0.2;

struct ModelDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};

// the Panda's inertia at a pose (armature included, as the follower's controller sees it)
control::JointMatrix panda_mass(const control::JointVector& q) {
  char error[512] = "";
  std::unique_ptr<mjModel, ModelDeleter> model(
      mj_loadXML((std::string(TELEOP_SOURCE_DIR) + "/config/models/panda.xml").c_str(), nullptr, error, sizeof error));
  if (!model) throw std::runtime_error(error);
  control::ArmDynamics dynamics(model.get(), "ee_site");
  control::ArmState state;
  state.q = q;
  dynamics.update(state);
  return dynamics.mass();
}

// the pose of the process test where the per-joint brake failed: shoulder near straight, so
// joints 0 and 2 turn about almost one axis
control::JointVector near_straight_shoulder() {
  control::JointVector q;
  q << 0.0, -0.0911, 0.0, -2.0142, 0.0, 3.4783, 0.7858;
  return q;
}

JointVector limits(double nm) {
  JointVector l{};
  for (size_t i = 0; i < control::kDof; ++i) l[i] = nm;
  return l;
}

// the velocity after `cycles` cycles of the rigid arm under `law`'s torque, held per cycle
template <typename Law>
control::JointVector coast(const control::JointMatrix& mass, control::JointVector dq, int cycles, Law law) {
  const Eigen::LDLT<control::JointMatrix> inertia(mass);
  for (int k = 0; k < cycles; ++k) dq += kCycleS * inertia.solve(law(dq));
  return dq;
}

TEST(SpeedBrake, StopsEveryModeOfACoupledArmByItsShareEachCycle) {
  const control::JointMatrix mass = panda_mass(near_straight_shoulder());
  const SpeedBrake brake(kShare, kCycleS);
  control::JointVector dq;
  dq << 2.0, 0.0, -2.0, 0.5, 0.0, 2.6, 0.0;  // the whip the shoulder's null space allows
  const control::JointVector stopped = coast(mass, dq, 40, [&](const control::JointVector& v) {
    control::JointVector tau = control::JointVector::Zero();
    brake.apply(mass, v, limits(1e6), tau);
    return tau;
  });
  // (1 - 0.2)^40 = 1.3e-4 of the speed is left, in every mode alike
  EXPECT_NEAR(stopped.norm() / dq.norm(), std::pow(1.0 - kShare, 40), 1e-9);
}

TEST(SpeedBrake, APerJointDamperOfTheSameShareIsUnstableThere) {
  // why the brake takes M(q) whole: D_i = share M_ii / cycle amplifies the coupled mode
  const control::JointMatrix mass = panda_mass(near_straight_shoulder());
  const control::JointVector damping = kShare * mass.diagonal() / kCycleS;
  control::JointVector dq;
  dq << 0.01, 0.0, -0.01, 0.0, 0.0, 0.0, 0.0;
  const control::JointVector grown =
      coast(mass, dq, 40, [&](const control::JointVector& v) -> control::JointVector { return -damping.cwiseProduct(v); });
  EXPECT_GT(grown.norm(), 100.0 * dq.norm());
}

TEST(SpeedBrake, WithinTheLimitsItKeepsItsDirectionAndOnlyTakesEnergy) {
  const control::JointMatrix mass = panda_mass(near_straight_shoulder());
  const SpeedBrake brake(kShare, kCycleS);
  control::JointVector dq;
  dq << 2.0, -1.0, -2.0, 1.5, 0.5, 2.6, -1.0;
  control::JointVector hold = control::JointVector::Zero();
  hold[1] = -30.0;  // e.g. gravity on the shoulder
  control::JointVector tau = hold;
  brake.apply(mass, dq, limits(87.0), tau);
  const control::JointVector applied = tau - hold;
  const control::JointVector unlimited = -(kShare / kCycleS) * (mass * dq);
  for (Eigen::Index i = 0; i < tau.size(); ++i) EXPECT_LE(std::abs(tau[i]), 87.0 + 1e-9) << "joint " << i;
  // a multiple of the unlimited brake, so its power is negative
  const double scale = applied.dot(unlimited) / unlimited.squaredNorm();
  EXPECT_GT(scale, 0.0);
  EXPECT_LT(scale, 1.0);
  EXPECT_NEAR((applied - scale * unlimited).norm(), 0.0, 1e-9);
  EXPECT_LT(applied.dot(dq), 0.0);
}

TEST(SpeedBrake, AJointTheHoldSaturatesDoesNotTakeTheBrakeAway) {
  const control::JointMatrix mass = panda_mass(near_straight_shoulder());
  const SpeedBrake brake(kShare, kCycleS);
  control::JointVector dq = control::JointVector::Zero();
  dq[3] = 1.0;
  control::JointVector tau = control::JointVector::Zero();
  // beyond its limit already (the limiter clips it), on the side the brake pushes it to
  tau[0] = std::copysign(100.0, -(mass * dq)[0]);
  const control::JointVector before = tau;
  brake.apply(mass, dq, limits(87.0), tau);
  EXPECT_LT(tau[3], before[3] - 1.0) << "the fast joint is still braked";
}

}  // namespace
}  // namespace teleop::follower
