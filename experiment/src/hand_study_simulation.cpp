#include "teleop/experiment/hand_study_simulation.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace teleop::experiment {
namespace {

constexpr size_t kArmJoints = HandStudySimulation::kArmJointNames.size();

hand::HandPlant configured_plant(const HandStudyConfig& c, const HandStudyRun& run) {
  hand::HandPlant plant(sim::MujocoModel::load(c.model_path), hand::HandCoupling::svh());
  if (run.link_inertia_kgm2 > 0.0) plant.set_link_inertia(run.link_inertia_kgm2);
  if (c.hand_torque_limit_nm > 0.0) plant.set_motor_torque_limit(c.hand_torque_limit_nm);
  if (!c.friction_cone.empty())
    plant.model()->opt.cone = c.friction_cone == "elliptic" ? mjCONE_ELLIPTIC : mjCONE_PYRAMIDAL;
  if (c.noslip_iterations >= 0) plant.model()->opt.noslip_iterations = c.noslip_iterations;
  return plant;
}

// The arm's joints and the hand's motors in a keyframe (the motors from the hand's 20 joints).
std::vector<double> keyframe_pose(const hand::HandPlant& plant, const std::string& keyframe) {
  const mjModel* m = plant.model();
  const mjtNum* qpos = m->key_qpos + static_cast<ptrdiff_t>(plant.mujoco().keyframe_id(keyframe)) * m->nq;
  std::vector<double> pose(kArmJoints + hand::kHandMotors);
  for (size_t i = 0; i < kArmJoints; ++i) {
    pose[i] = qpos[plant.mujoco().joint_qpos_address(HandStudySimulation::kArmJointNames[i])];
  }
  hand::HandJointVector q{};
  for (size_t j = 0; j < hand::kHandJoints; ++j) q[j] = qpos[plant.index().qpos[j]];
  const hand::HandMotorVector motors = plant.coupling().motors_from_joints(q);
  for (size_t k = 0; k < hand::kHandMotors; ++k) {
    if (motors[k] < plant.index().motor_min_rad[k] || motors[k] > plant.index().motor_max_rad[k]) {
      throw std::runtime_error("keyframe '" + keyframe + "' of " + plant.mujoco().path() + " puts motor " +
                               std::string(hand::kHandMotorNames[k]) + " outside the range its joints allow");
    }
    pose[kArmJoints + k] = motors[k];
  }
  return pose;
}

control::MinJerkPath make_path(const hand::HandPlant& plant, const HandStudyConfig& c) {
  control::MinJerkPath path(keyframe_pose(plant, c.path.front().keyframe));
  for (size_t i = 1; i < c.path.size(); ++i) path.then(keyframe_pose(plant, c.path[i].keyframe), c.path[i].move_s);
  return path;
}

}  // namespace

// the PDs are designed on the inertias at the pose the study holds: the arm's here, with the
// plant put there first, the hand's in the next member's constructor, then the start
HandStudySimulation::HandStudySimulation(const HandStudyConfig& config, const HandStudyRun& run)
    : plant_(configured_plant(config, run)),
      path_(make_path(plant_, config)),
      arm_([&] {
        plant_.mujoco().reset(config.path.back().keyframe);
        std::array<ArmJoint, kArmJoints> arm;
        for (size_t i = 0; i < kArmJoints; ++i) {
          arm[i].qpos = plant_.mujoco().joint_qpos_address(kArmJointNames[i]);
          arm[i].dof = plant_.mujoco().joint_dof_address(kArmJointNames[i]);
          arm[i].actuator = plant_.mujoco().actuator_id(kArmJointNames[i]);
          // the diagonal of M: each joint with the others held by their own PDs
          const double inertia = plant_.data()->qM[plant_.model()->dof_Madr[arm[i].dof]];
          arm[i].gains = hand::pd_gains_for(inertia, config.arm_bandwidth_radps, config.damping_ratio);
        }
        return arm;
      }()),
      hand_control_(plant_, run.coupling, config.hand_bandwidth_radps, config.damping_ratio,
                    config.servo_bandwidth_radps),
      tip_geom_(plant_.mujoco().geom_id("svh_index_distal")),
      panel_geom_(plant_.mujoco().geom_id("panel")),
      ref_(path_.size()),
      dref_(path_.size()) {
  plant_.mujoco().reset(config.path.front().keyframe);
}

double HandStudySimulation::time_s() const { return static_cast<double>(steps_) * plant_.model()->opt.timestep; }

void HandStudySimulation::step() {
  path_.sample(time_s(), ref_, dref_);
  std::copy(ref_.begin() + kArmJoints, ref_.end(), m_ref_.begin());
  std::copy(dref_.begin() + kArmJoints, dref_.end(), dm_ref_.begin());
  plant_.begin_step();
  // the arm: a PD per joint plus its bias force (gravity, Coriolis), as the UR's own controller
  // compensates its gravity
  mjData* d = plant_.data();
  for (size_t i = 0; i < kArmJoints; ++i) {
    const ArmJoint& a = arm_[i];
    d->ctrl[a.actuator] =
        hand::pd_torque(a.gains, ref_[i], dref_[i], d->qpos[a.qpos], d->qvel[a.dof]) + d->qfrc_bias[a.dof];
  }
  hand_control_.apply(plant_, m_ref_, dm_ref_);
  plant_.end_step();
  ++steps_;
}

bool HandStudySimulation::foreign_contact() const {
  const mjData* d = plant_.data();
  for (int i = 0; i < d->ncon; ++i) {
    const mjContact& c = d->contact[i];
    const bool ours =
        (c.geom1 == tip_geom_ && c.geom2 == panel_geom_) || (c.geom1 == panel_geom_ && c.geom2 == tip_geom_);
    if (!ours) return true;
  }
  return false;
}

}  // namespace teleop::experiment
