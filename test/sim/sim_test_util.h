#pragma once
// Helpers shared by the tests of teleop::sim and of the MuJoCo models in config/models/.

#include <mujoco/mujoco.h>

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "teleop/sim/mujoco_model.h"

namespace teleop::sim::test {

/// Path of a file in config/models/.
inline std::string model_path(const std::string& name) {
  return std::string(TELEOP_SOURCE_DIR) + "/config/models/" + name;
}

inline Eigen::Vector3d vec3(const mjtNum* p) { return {p[0], p[1], p[2]}; }

/// A site's world pose from the current mjData (after mj_kinematics or mj_forward).
inline Eigen::Isometry3d site_pose(const mjData* d, int site) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  Eigen::Matrix3d rotation;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) rotation(r, c) = d->site_xmat[9 * site + 3 * r + c];
  }
  pose.linear() = rotation;
  pose.translation() = vec3(d->site_xpos + 3 * site);
  return pose;
}

/// Steps the model for `seconds` under a simple controller: every joint-torque motor applies the
/// bias force of its joint (gravity and Coriolis compensation, computed for the state of that
/// very step), plus J^T force for a force (world frame, N) on `site`, minus damping * qvel.
/// Other actuators get ctrl 0. Calls `each_step` after every step, if given.
template <typename EachStep>
void drive_site(MujocoModel& sim, int site, const Eigen::Vector3d& force_n, double damping_nms, double seconds,
                EachStep&& each_step) {
  const mjModel* m = sim.model();
  mjData* d = sim.data();
  std::vector<mjtNum> jacp(3 * static_cast<size_t>(m->nv));
  const int steps = static_cast<int>(seconds / m->opt.timestep + 0.5);
  for (int k = 0; k < steps; ++k) {
    mj_step1(m, d);  // positions and velocities: qfrc_bias for this state
    if (site >= 0) mj_jacSite(m, d, jacp.data(), nullptr, site);
    for (int a = 0; a < m->nu; ++a) {
      d->ctrl[a] = 0;
      if (m->actuator_trntype[a] != mjTRN_JOINT || m->actuator_biastype[a] != mjBIAS_NONE) continue;
      const int dof = m->jnt_dofadr[m->actuator_trnid[2 * a]];
      double tau = d->qfrc_bias[dof] - damping_nms * d->qvel[dof];
      if (site >= 0) {
        for (int r = 0; r < 3; ++r) tau += jacp[static_cast<size_t>(r * m->nv + dof)] * force_n[r];
      }
      d->ctrl[a] = tau;
    }
    mj_step2(m, d);
    each_step();
  }
}

inline void drive_site(MujocoModel& sim, int site, const Eigen::Vector3d& force_n, double damping_nms, double seconds) {
  drive_site(sim, site, force_n, damping_nms, seconds, [] {});
}

/// Whether a contact between the two geoms is active in the current mjData.
inline bool in_contact(const mjData* d, int geom_a, int geom_b) {
  for (int i = 0; i < d->ncon; ++i) {
    const mjContact& c = d->contact[i];
    if ((c.geom1 == geom_a && c.geom2 == geom_b) || (c.geom1 == geom_b && c.geom2 == geom_a)) return true;
  }
  return false;
}

/// Whether any contact involves a geom of the body `body` or of its descendants.
inline bool subtree_in_contact_with(const mjModel* m, const mjData* d, int body, int geom) {
  auto in_subtree = [&](int g) {
    for (int b = m->geom_bodyid[g]; b > 0; b = m->body_parentid[b]) {
      if (b == body) return true;
    }
    return false;
  };
  for (int i = 0; i < d->ncon; ++i) {
    const mjContact& c = d->contact[i];
    if ((c.geom1 == geom && in_subtree(c.geom2)) || (c.geom2 == geom && in_subtree(c.geom1))) return true;
  }
  return false;
}

}  // namespace teleop::sim::test
