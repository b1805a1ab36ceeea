#include "teleop/control/controllers.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "allocation_counter.h"
#include "control_test_util.h"
#include "teleop/control/controller_switch.h"

namespace teleop::control {
namespace {

using test::panda;
using test::ready_q;
using test::state_of;

constexpr double kPi = 3.14159265358979323846;

TEST(GravityCompensation, HoldsTheReadyPoseWhenUnloaded) {
  auto sim = panda();
  const mjModel* m = sim.model();
  mjData* d = sim.data();
  ArmDynamics dyn(m, "ee_site");
  GravityCompensation gc(dyn);
  const ArmCommand cmd;
  double drift = 0;
  for (int k = 0; k < 5000; ++k) {  // 5 s
    test::step(m, d, [&](const mjData* dd) { return gc.compute(state_of(dd), cmd); });
    drift = std::max(drift, (state_of(d).q - ready_q()).cwiseAbs().maxCoeff());
  }
  std::printf("gravity compensation: max joint drift over 5 s = %.3g rad (bound 1e-3)\n", drift);
  EXPECT_LT(drift, 1e-3);
}

TEST(JointImpedance, StepResponseMatchesSecondOrderWhenJointSevenSteps) {
  auto sim = panda();
  const mjModel* m = sim.model();
  mjData* d = sim.data();
  ArmDynamics dyn(m, "ee_site");
  dyn.update(state_of(d));
  // Effective inertia of joint 7 with the other joints held stiffly: M_77 of the ready pose,
  // which MuJoCo's mj_crb already contains the rotor armature in (M_77 = link inertia about the
  // axis + armature). Were the other joints free it would be 1 / (M^-1)_77 instead.
  const double m77 = dyn.mass()(6, 6);
  const double m77_free = 1.0 / dyn.mass().inverse()(6, 6);
  const double k7 = 4.0;
  const double zeta = 0.2;
  const double d7 = 2 * zeta * std::sqrt(k7 * m77);
  JointImpedance::Gains gains;
  gains.stiffness << 400, 400, 400, 400, 100, 100, k7;
  gains.damping << 40, 40, 40, 40, 5, 5, d7;
  JointImpedance ji(dyn, gains);
  ArmCommand cmd;
  cmd.q_d = ready_q();
  cmd.q_d[6] += 0.2;

  std::vector<double> peak_t;
  std::vector<double> peak_a;
  double prev_v = 0;
  for (int k = 0; k < 1500; ++k) {
    test::step(m, d, [&](const mjData* dd) { return ji.compute(state_of(dd), cmd); });
    const double v = d->qvel[6];
    if (k > 0 && prev_v != 0 && (v > 0) != (prev_v > 0)) {  // extremum between the two samples
      peak_t.push_back((k + 1) * m->opt.timestep);
      peak_a.push_back(std::abs(d->qpos[6] - cmd.q_d[6]));
    }
    prev_v = v;
  }
  ASSERT_GE(peak_t.size(), 3u);
  const double period = peak_t[2] - peak_t[0];
  const double delta = std::log(peak_a[0] / peak_a[2]);
  const double zeta_meas = delta / std::sqrt(4 * kPi * kPi + delta * delta);
  const double wn_meas = 2 * kPi / (period * std::sqrt(1 - zeta_meas * zeta_meas));
  const double wn = std::sqrt(k7 / m77);
  std::printf(
      "joint impedance, joint 7: M_77 = %.5f kg m^2 (1/(M^-1)_77 = %.5f), K = %.1f, D = %.4f\n"
      "  ideal wn = %.3f rad/s zeta = %.3f; measured wn = %.3f rad/s zeta = %.3f\n",
      m77, m77_free, k7, d7, wn, zeta, wn_meas, zeta_meas);
  EXPECT_NEAR(wn_meas, wn, 0.1 * wn);
  EXPECT_NEAR(zeta_meas, zeta, 0.1 * zeta);
}

struct CartesianRun {
  Eigen::Vector3d expected;
  Eigen::Vector3d displacement;
};

TEST(CartesianImpedance, DisplacesByComplianceTimesForceWhenPushedAtTheFlange) {
  auto sim = panda();
  const mjModel* m = sim.model();
  mjData* d = sim.data();
  const int site = sim.site_id("ee_site");
  ArmDynamics dyn(m, "ee_site");
  dyn.update(state_of(d));
  CartesianImpedance::Gains gains;
  gains.translational_stiffness = {500, 500, 500};
  gains.rotational_stiffness = {30, 30, 30};
  gains.nullspace_stiffness = JointVector::Constant(10);
  gains.nullspace_damping = JointVector::Constant(5);
  CartesianImpedance ci(dyn, gains);
  ArmCommand cmd;
  cmd.x_d = dyn.ee_position();
  cmd.orientation_d = Eigen::Quaterniond(dyn.ee_rotation());
  cmd.q_rest = ready_q();
  const Eigen::Vector3d force(8, -6, 10);
  const Eigen::Vector3d expected = force.cwiseQuotient(gains.translational_stiffness);

  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  int n = 0;
  for (int k = 0; k < 3000; ++k) {
    test::step(m, d, [&](mjData* dd) {
      test::apply_site_force(m, dd, site, force);
      return ci.compute(state_of(dd), cmd);
    });
    if (k >= 2500) {
      mean += Eigen::Vector3d(d->site_xpos[3 * site], d->site_xpos[3 * site + 1], d->site_xpos[3 * site + 2]);
      ++n;
    }
  }
  const Eigen::Vector3d dx = mean / n - cmd.x_d;
  std::printf("cartesian impedance: F = (%.1f %.1f %.1f) N, K = 500 N/m\n"
              "  K^-1 F = (%.5f %.5f %.5f) m, measured = (%.5f %.5f %.5f) m, rel. error %.3f %%\n",
              force.x(), force.y(), force.z(), expected.x(), expected.y(), expected.z(), dx.x(), dx.y(), dx.z(),
              100 * (dx - expected).norm() / expected.norm());
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(dx[i], expected[i], 0.1 * std::abs(expected[i])) << i;
  EXPECT_LT(ci.last_error().tail<3>().norm(), 0.01);  // orientation held (a pure force)
}

TEST(PositionPd, LeavesTheStaticErrorOfGravityOverStiffnessWhenHolding) {
  auto sim = panda();
  const mjModel* m = sim.model();
  mjData* d = sim.data();
  ArmDynamics dyn(m, "ee_site");
  PositionPd::Gains gains;
  gains.kp << 2000, 2000, 2000, 2000, 100, 100, 100;
  gains.kd << 100, 100, 100, 100, 2, 2, 2;
  PositionPd pd(gains);
  ArmCommand cmd;
  cmd.q_d = ready_q();
  for (int k = 0; k < 2000; ++k) {
    test::step(m, d, [&](const mjData* dd) { return pd.compute(state_of(dd), cmd); });
  }
  dyn.update(state_of(d));
  const JointVector predicted = -dyn.gravity().cwiseQuotient(gains.kp);  // q - q_d = -g / Kp
  const JointVector error = state_of(d).q - cmd.q_d;
  for (int i = 0; i < kDof; ++i) {
    EXPECT_NEAR(error[i], predicted[i], 0.1 * std::abs(predicted[i]) + 1e-5) << i;
  }
}

TEST(Controllers, DoNotAllocateWhenComputing) {
  auto sim = panda();
  ArmDynamics dyn(sim.model(), "ee_site");
  GravityCompensation gc(dyn);
  JointImpedance ji(dyn, {JointVector::Constant(100), JointVector::Constant(10)});
  CartesianImpedance ci(dyn, CartesianImpedance::Gains{});
  PositionPd pd({JointVector::Constant(100), JointVector::Constant(10)});
  ControllerSwitch sw(0.001, 0.05);
  sw.add(ji);
  sw.add(ci);
  sw.add(gc);
  ArmState s = state_of(sim.data());
  dyn.update(s);
  ArmCommand cmd;
  cmd.q_d = ready_q();
  cmd.q_rest = ready_q();
  cmd.x_d = dyn.ee_position();
  JointVector sum = JointVector::Zero();
  {
    teleop::test::ScopedAllocationCounter counter;
    for (int k = 0; k < 1000; ++k) {
      s.q[1] = ready_q()[1] + 1e-4 * k;
      s.dq[2] = 1e-3 * k;
      if (k % 100 == 10) sw.select((k / 100) % 3);
      sum += gc.compute(s, cmd) + ji.compute(s, cmd) + ci.compute(s, cmd) + pd.compute(s, cmd) + sw.compute(s, cmd);
    }
    EXPECT_EQ(counter.count(), 0u);
  }
  EXPECT_TRUE(sum.allFinite());
}

}  // namespace
}  // namespace teleop::control
