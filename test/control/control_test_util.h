#pragma once
// Shared by the teleop::control tests: the Panda model at its "ready" pose, stepped at 1 ms with
// joint torques through its motors (gear 1, ctrl = link-side torque).

#include <mujoco/mujoco.h>

#include <Eigen/Core>
#include <string>

#include "teleop/control/types.h"
#include "teleop/sim/mujoco_model.h"

namespace teleop::control::test {

inline std::string panda_path() { return std::string(TELEOP_SOURCE_DIR) + "/config/models/panda.xml"; }

/// The Panda at "ready". Joint friction (frictionloss, a MuJoCo constraint the rigid-body model
/// of the controllers does not contain) is switched off: these tests measure the laws against
/// the rigid-body model, and an estimator would (rightly) report friction as external torque.
inline sim::MujocoModel panda() {
  auto sim = sim::MujocoModel::load(panda_path());
  for (int i = 0; i < sim.model()->nv; ++i) sim.model()->dof_frictionloss[i] = 0;
  sim.reset("ready");
  return sim;
}

inline ArmState state_of(const mjData* d) {
  ArmState s;
  for (int i = 0; i < kDof; ++i) {
    s.q[i] = d->qpos[i];
    s.dq[i] = d->qvel[i];
  }
  return s;
}

inline JointVector ready_q() {
  JointVector q;
  q << 0, -0.78539816339744831, 0, -2.3561944901923448, 0, 1.5707963267948966, 0.78539816339744831;
  return q;
}

/// Sets a pure force `force` (world, N) at site `site` as xfrc_applied on the site's body: the
/// force at the body's CoM plus the moment (p_site - p_com) x force. Uses the kinematics in `d`.
inline void apply_site_force(const mjModel* m, mjData* d, int site, const Eigen::Vector3d& force) {
  const int body = m->site_bodyid[site];
  const Eigen::Vector3d arm(d->site_xpos[3 * site] - d->xipos[3 * body], d->site_xpos[3 * site + 1] - d->xipos[3 * body + 1],
                            d->site_xpos[3 * site + 2] - d->xipos[3 * body + 2]);
  const Eigen::Vector3d moment = arm.cross(force);
  for (int i = 0; i < 3; ++i) {
    d->xfrc_applied[6 * body + i] = force[i];
    d->xfrc_applied[6 * body + 3 + i] = moment[i];
  }
}

/// One 1 ms step in two halves: step1 (kinematics of the current state), `before(d)` (forces,
/// controller: returns the torque), ctrl = torque, step2. Returns the actuator torque that acted.
template <typename Before>
JointVector step(const mjModel* m, mjData* d, Before&& before) {
  mj_step1(m, d);
  const JointVector tau = before(d);
  for (int i = 0; i < kDof; ++i) d->ctrl[i] = tau[i];
  mj_step2(m, d);
  JointVector applied;
  for (int i = 0; i < kDof; ++i) applied[i] = d->qfrc_actuator[i];
  return applied;
}

}  // namespace teleop::control::test
