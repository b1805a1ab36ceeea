#include "teleop/follower/mujoco_hardware.h"

#include <cmath>
#include <algorithm>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <vector>

namespace teleop::follower {
namespace {

void delete_data(mjData* d) { mj_deleteData(d); }

}  // namespace

MujocoHardware::MujocoHardware(const MujocoHardwareConfig& config)
    : sim_(sim::MujocoModel::load(config.model_path)), rest_(nullptr, delete_data) {
  const mjModel* m = sim_.model();
  if (!config.keyframe.empty()) sim_.reset(config.keyframe);
  rest_.reset(mj_makeData(m));
  name_ = "mujoco:" + std::filesystem::path(config.model_path).filename().string();

  // the arm: hinge joints driven by actuators, in actuator order
  arm_ = sim::find_actuated_joints(m, config.model_path);

  const double steps = config.period_s / m->opt.timestep;
  substeps_ = static_cast<int>(std::lround(steps));
  if (substeps_ < 1 || std::abs(steps - substeps_) > 1e-6) {
    throw std::runtime_error(config.model_path + ": timestep " + std::to_string(m->opt.timestep) +
                             " s does not divide the control period " + std::to_string(config.period_s) + " s");
  }
  const int site = mj_name2id(m, mjOBJ_SITE, "ee_site");
  ee_body_ = site >= 0 ? m->site_bodyid[site] : m->jnt_bodyid[m->actuator_trnid[2 * arm_.actuator[arm_.count - 1]]];
  mj_forward(m, sim_.data());
}

void MujocoHardware::place(const JointVector& q_rad) {
  mjData* d = sim_.data();
  for (size_t i = 0; i < arm_.count; ++i) {
    d->qpos[arm_.qpos[i]] = q_rad[i];
    d->qvel[arm_.dof[i]] = 0.0;
  }
  mj_forward(sim_.model(), d);
}

void MujocoHardware::compute_gravity() {
  const mjModel* m = sim_.model();
  // the same pose at rest: the bias forces are then gravity alone
  mju_copy(rest_->qpos, sim_.data()->qpos, m->nq);
  mju_zero(rest_->qvel, m->nv);
  mj_kinematics(m, rest_.get());
  mj_comPos(m, rest_.get());
  mj_rne(m, rest_.get(), 0, rest_->qfrc_bias);
  for (size_t i = 0; i < arm_.count; ++i) gravity_nm_[i] = rest_->qfrc_bias[arm_.dof[i]];
}

HardwareStatus MujocoHardware::write(const JointVector& tau_nm) {
  const mjModel* m = sim_.model();
  mjData* d = sim_.data();
  compute_gravity();
  for (size_t i = 0; i < arm_.count; ++i) {
    if (!std::isfinite(tau_nm[i])) return HardwareStatus::kFault;
    d->ctrl[arm_.actuator[i]] = tau_nm[i] + gravity_nm_[i];
  }
  for (int s = 0; s < substeps_; ++s) mj_step(m, d);
  return HardwareStatus::kOk;
}

void MujocoHardware::compute_external_wrench(ArmState& state) const {
  const mjModel* m = sim_.model();
  const mjData* d = sim_.data();
  state.force_ext_n = {0, 0, 0};
  state.torque_ext_nm = {0, 0, 0};
  const mjtNum* ee = d->xpos + 3 * ee_body_;
  for (int c = 0; c < d->ncon; ++c) {
    const mjContact& con = d->contact[c];
    const int b1 = m->geom_bodyid[con.geom1];
    const int b2 = m->geom_bodyid[con.geom2];
    // contacts of the end effector's body with anything else
    const double sign = b2 == ee_body_ ? 1.0 : (b1 == ee_body_ ? -1.0 : 0.0);
    if (sign == 0.0 || b1 == b2) continue;
    mjtNum local[6];
    mj_contactForce(m, d, c, local);
    // contact frame rows are its axes in world coordinates; the force acts on geom2 along them
    mjtNum world[3];
    mju_mulMatTVec(world, con.frame, local, 3, 3);
    const mjtNum r[3] = {con.pos[0] - ee[0], con.pos[1] - ee[1], con.pos[2] - ee[2]};
    mjtNum moment[3];
    mju_cross(moment, r, world);
    for (int k = 0; k < 3; ++k) {
      state.force_ext_n[static_cast<size_t>(k)] += sign * world[k];
      state.torque_ext_nm[static_cast<size_t>(k)] += sign * moment[k];
    }
  }
}

HardwareLimits MujocoHardware::limits() const {
  const mjModel* m = sim_.model();
  constexpr double kInf = std::numeric_limits<double>::infinity();
  HardwareLimits l;
  for (size_t i = 0; i < arm_.count; ++i) {
    const int a = arm_.actuator[i];
    const int joint = m->actuator_trnid[2 * a];
    const bool limited = m->jnt_limited[joint] != 0;
    l.q_min_rad[i] = limited ? m->jnt_range[2 * joint] : -kInf;
    l.q_max_rad[i] = limited ? m->jnt_range[2 * joint + 1] : kInf;
    // ctrl is the link-side torque (gear 1 motors); the gear scales it otherwise
    const double gear = std::abs(m->actuator_gear[6 * a]);
    l.max_torque_nm[i] = m->actuator_ctrllimited[a] != 0
                             ? gear * std::max(std::abs(m->actuator_ctrlrange[2 * a]), std::abs(m->actuator_ctrlrange[2 * a + 1]))
                             : kInf;
  }
  return l;
}

HardwareStatus MujocoHardware::read(ArmState& state) {
  const mjData* d = sim_.data();
  for (size_t i = 0; i < arm_.count; ++i) {
    state.q_rad[i] = d->qpos[arm_.qpos[i]];
    state.dq_radps[i] = d->qvel[arm_.dof[i]];
    state.tau_measured_nm[i] = d->actuator_force[arm_.actuator[i]];
    // contacts and joint limits acting on the joint, from the last step
    state.tau_ext_nm[i] = d->qfrc_constraint[arm_.dof[i]];
  }
  compute_external_wrench(state);
  return HardwareStatus::kOk;
}

}  // namespace teleop::follower
