#include "teleop/robot/mujoco_hardware.h"

#include <cmath>
#include <algorithm>
#include <limits>
#include <stdexcept>

namespace teleop::robot {

MujocoHardware::MujocoHardware(const MujocoHardwareConfig& config)
    : MujocoHardware(std::make_shared<MujocoScene>(config), config, true) {}

MujocoHardware::MujocoHardware(std::shared_ptr<MujocoScene> scene, const MujocoHardwareConfig& config)
    : MujocoHardware(std::move(scene), config, false) {}

MujocoHardware::MujocoHardware(std::shared_ptr<MujocoScene> scene, const MujocoHardwareConfig& config, bool steps_scene)
    : scene_(std::move(scene)), steps_scene_(steps_scene), gravity_compensated_(config.gravity_compensated) {
  const mjModel* m = scene_->simulation().model();
  name_ = "mujoco:" + scene_->file_name() + (config.joint_prefix.empty() ? "" : ":" + config.joint_prefix + "*");
  // the arm: hinge joints driven by actuators, in actuator order
  arm_ = sim::find_actuated_joints(m, config.model_path, config.joint_prefix);
  const int site = mj_name2id(m, mjOBJ_SITE, config.ee_site.c_str());
  if (site < 0 && !config.joint_prefix.empty()) {
    throw std::runtime_error(config.model_path + ": no site " + config.ee_site + " for the arm " + config.joint_prefix + "*");
  }
  ee_body_ = site >= 0 ? m->site_bodyid[site] : m->jnt_bodyid[m->actuator_trnid[2 * arm_.actuator[arm_.count - 1]]];
  if (const auto& real = scene_->real_robot()) {
    // each arm's sensors a stream of their own, named by the arm's first motor
    noise_.emplace(real->sensor_noise, sim::derived_seed(real->seed, 1 + static_cast<uint64_t>(arm_.actuator[0])));
  }
}

void MujocoHardware::place(const JointVector& q_rad) {
  mjData* d = scene_->simulation().data();
  for (size_t i = 0; i < arm_.count; ++i) {
    d->qpos[arm_.qpos[i]] = q_rad[i];
    d->qvel[arm_.dof[i]] = 0.0;
  }
  scene_->state_changed();
}

void MujocoHardware::place_joints(const JointVector& q_rad, const std::array<bool, kMaxJoints>& held) {
  mjData* d = scene_->simulation().data();
  bool any = false;
  for (size_t k = 0; k < arm_.count; ++k) {
    if (!held[k]) continue;
    d->qpos[arm_.qpos[k]] = q_rad[k];
    d->qvel[arm_.dof[k]] = 0.0;
    any = true;
  }
  if (any) scene_->state_changed();
}

HardwareStatus MujocoHardware::write(const JointVector& tau_nm) {
  mjData* d = scene_->simulation().data();
  const mjtNum* gravity = gravity_compensated_ ? scene_->gravity() : nullptr;
  HardwareStatus status = HardwareStatus::kOk;
  for (size_t i = 0; i < arm_.count; ++i) {
    if (!std::isfinite(tau_nm[i])) {
      status = HardwareStatus::kFault;
      break;
    }
    d->ctrl[arm_.actuator[i]] = tau_nm[i] + (gravity != nullptr ? gravity[arm_.dof[i]] : 0.0);
  }
  // a shared scene steps once all its arms wrote, whatever each of them wrote
  if (steps_scene_) scene_->step();
  return status;
}

void MujocoHardware::compute_external_wrench(ArmState& state) const {
  const mjModel* m = scene_->simulation().model();
  const mjData* d = scene_->simulation().data();
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
  const mjModel* m = scene_->simulation().model();
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
  const mjData* d = scene_->simulation().data();
  for (size_t i = 0; i < arm_.count; ++i) {
    state.q_rad[i] = d->qpos[arm_.qpos[i]];
    state.dq_radps[i] = d->qvel[arm_.dof[i]];
    state.tau_measured_nm[i] = d->actuator_force[arm_.actuator[i]];
    // contacts and joint limits acting on the joint, from the last step
    state.tau_ext_nm[i] = d->qfrc_constraint[arm_.dof[i]];
  }
  if (noise_) {
    for (size_t i = 0; i < arm_.count; ++i) {
      state.q_rad[i] += noise_->q_rad();
      state.dq_radps[i] += noise_->dq_radps();
      state.tau_measured_nm[i] += noise_->tau_nm();
    }
  }
  compute_external_wrench(state);
  return HardwareStatus::kOk;
}

}  // namespace teleop::robot
