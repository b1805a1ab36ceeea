#include "teleop/control/controller_switch.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "control_test_util.h"

namespace teleop::control {
namespace {

using test::panda;
using test::ready_q;
using test::state_of;

constexpr double kPi = 3.14159265358979323846;

// The stated bound of the switch on the Panda at 1 ms with a 50 ms blend, for the motion below
// (a 0.8 Hz, 0.3 rad sinusoid on four joints, past its start-up): no joint's torque changes by
// more than this from one cycle to the next, switches included. The gap between the modes at the
// switches reaches ~19 Nm, so an unblended switch would step by that much.
constexpr double kMaxStepNm = 1.0;

TEST(ControllerSwitch, BoundsTheTorqueChangeWhenSwitchingModesAtAMovingState) {
  auto sim = panda();
  const mjModel* m = sim.model();
  mjData* d = sim.data();
  const double h = m->opt.timestep;
  ArmDynamics dyn(m, "ee_site");
  dyn.update(state_of(d));
  JointImpedance::Gains jg;
  jg.stiffness << 300, 300, 300, 300, 50, 50, 20;
  jg.damping << 30, 30, 30, 30, 3, 3, 1;
  JointImpedance ji(dyn, jg);
  CartesianImpedance::Gains cg;
  cg.nullspace_stiffness = JointVector::Constant(10);
  cg.nullspace_damping = JointVector::Constant(5);
  CartesianImpedance ci(dyn, cg);
  GravityCompensation gc(dyn);
  ControllerSwitch sw(h, 0.05);
  const int joint_mode = sw.add(ji);
  const int cart_mode = sw.add(ci);
  const int grav_mode = sw.add(gc);

  ArmCommand cmd;
  cmd.x_d = dyn.ee_position();
  cmd.orientation_d = Eigen::Quaterniond(dyn.ee_rotation());
  cmd.q_rest = ready_q();
  Controller* ctrl[3] = {&ji, &ci, &gc};

  JointVector last = JointVector::Zero();
  JointVector last_each[3];
  double max_step = 0;
  double max_gap = 0;
  double max_violation = -1;
  for (int k = 0; k < 1400; ++k) {
    const double t = k * h;
    if (k == 500) sw.select(cart_mode);
    if (k == 1000) sw.select(grav_mode);
    const double w = 2 * kPi * 0.8;
    cmd.q_d = ready_q();
    cmd.dq_d.setZero();
    for (int j : {0, 1, 3, 5}) {
      cmd.q_d[j] += 0.3 * std::sin(w * t);
      cmd.dq_d[j] = 0.3 * w * std::cos(w * t);
    }
    test::step(m, d, [&](const mjData* dd) {
      const ArmState s = state_of(dd);
      const int from = sw.from_mode();
      const int to = sw.mode();
      const JointVector tau = sw.compute(s, cmd);
      JointVector each[3];
      for (int c = 0; c < 3; ++c) each[c] = ctrl[c]->compute(s, cmd);
      if (k > 0) {
        const JointVector change = (tau - last).cwiseAbs();
        // after the start-up transient (the arm starting from rest into the sinusoid)
        if (k >= 200) max_step = std::max(max_step, change.maxCoeff());
        if (from != to) {
          max_gap = std::max(max_gap, (each[to] - each[from]).cwiseAbs().maxCoeff());
          // the per-joint bound of controller_switch.h (delta = 0 here: no switch within a blend)
          const JointVector own = (each[from] - last_each[from]).cwiseAbs().cwiseMax((each[to] - last_each[to]).cwiseAbs());
          const JointVector bound = own + (h / 0.05) * (last_each[to] - last_each[from]).cwiseAbs();
          max_violation = std::max(max_violation, (change - bound).maxCoeff());
        }
      }
      last = tau;
      for (int c = 0; c < 3; ++c) last_each[c] = each[c];
      return tau;
    });
  }
  EXPECT_EQ(joint_mode, 0);
  EXPECT_EQ(sw.mode(), grav_mode);
  EXPECT_FALSE(sw.blending());
  std::printf("controller switch: largest torque gap between the two modes during a blend %.2f Nm,\n"
              "  largest per-cycle torque change %.3f Nm (stated bound %.1f Nm), worst excess over the\n"
              "  per-cycle formula bound %.2g Nm\n",
              max_gap, max_step, kMaxStepNm, max_violation);
  EXPECT_GT(max_gap, kMaxStepNm);  // a hard switch would have broken the bound
  EXPECT_LT(max_step, kMaxStepNm);
  EXPECT_LT(max_violation, 1e-9);
}

TEST(ControllerSwitch, StaysContinuousWhenSwitchedAgainDuringABlend) {
  auto sim = panda();
  ArmDynamics dyn(sim.model(), "ee_site");
  ArmState s = state_of(sim.data());
  dyn.update(s);
  JointImpedance ji(dyn, {JointVector::Constant(100), JointVector::Constant(10)});
  GravityCompensation gc(dyn);
  PositionPd pd({JointVector::Constant(100), JointVector::Constant(10)});
  ControllerSwitch sw(0.001, 0.05);
  sw.add(ji);
  sw.add(gc);
  sw.add(pd);
  ArmCommand cmd;
  cmd.q_d = ready_q();
  cmd.q_d[0] += 0.2;  // joint impedance and PD pull, gravity compensation does not
  JointVector last = sw.compute(s, cmd);
  double max_step = 0;
  for (int k = 0; k < 200; ++k) {
    if (k == 10) sw.select(1);
    if (k == 30) sw.select(2);  // mid-blend
    const JointVector tau = sw.compute(s, cmd);
    max_step = std::max(max_step, (tau - last).cwiseAbs().maxCoeff());
    last = tau;
  }
  EXPECT_EQ(sw.mode(), 2);
  EXPECT_FALSE(sw.blending());
  EXPECT_LT((last - pd.compute(s, cmd)).norm(), 1e-12);
  // gap <= 100 Nm/rad * 0.2 rad + g: spread over 50 cycles
  EXPECT_LT(max_step, (20.0 + dyn.gravity().cwiseAbs().maxCoeff()) / 50 + 1e-9);
}

}  // namespace
}  // namespace teleop::control
