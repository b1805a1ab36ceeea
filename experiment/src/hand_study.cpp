// One run of the SVH hand study: the scene, the paper's control, the motion and the samples.
#include "teleop/experiment/hand_study.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "teleop/experiment/metrics.h"
#include "teleop/hand/hand_plant.h"
#include "teleop/hand/min_jerk.h"

namespace teleop::experiment {
namespace {

constexpr size_t kArmJoints = 6;
constexpr std::array<const char*, kArmJoints> kArmJointNames = {
    "shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint", "wrist_1_joint", "wrist_2_joint", "wrist_3_joint"};
// the pose the trajectory moves: the 6 arm joints, then the 9 motors
constexpr size_t kPoseSize = kArmJoints + hand::kHandMotors;

// The arm: a PD per joint plus its bias force (gravity, Coriolis), as the UR's own controller
// compensates its gravity; designed on the diagonal of M at the current state.
struct ArmControl {
  std::array<int, kArmJoints> qpos{};
  std::array<int, kArmJoints> dof{};
  std::array<int, kArmJoints> actuator{};
  std::array<hand::PdGains, kArmJoints> gains{};
};

ArmControl design_arm(const sim::MujocoModel& sim, double bandwidth_radps, double damping_ratio) {
  ArmControl arm;
  for (size_t i = 0; i < kArmJoints; ++i) {
    arm.qpos[i] = sim.joint_qpos_address(kArmJointNames[i]);
    arm.dof[i] = sim.joint_dof_address(kArmJointNames[i]);
    arm.actuator[i] = sim.actuator_id(kArmJointNames[i]);
    const double inertia = sim.data()->qM[sim.model()->dof_Madr[arm.dof[i]]];
    arm.gains[i] = hand::pd_gains_for(inertia, bandwidth_radps, damping_ratio);
  }
  return arm;
}

void apply_arm(const ArmControl& arm, mjData* d, const std::vector<double>& q_ref, const std::vector<double>& dq_ref) {
  for (size_t i = 0; i < kArmJoints; ++i) {
    const double q = d->qpos[arm.qpos[i]];
    const double dq = d->qvel[arm.dof[i]];
    d->ctrl[arm.actuator[i]] = hand::pd_torque(arm.gains[i], q_ref[i], dq_ref[i], q, dq) + d->qfrc_bias[arm.dof[i]];
  }
}

// The arm's joints and the hand's motors in a keyframe (the motors from the hand's 20 joints).
std::vector<double> keyframe_pose(const hand::HandPlant& plant, const std::string& keyframe) {
  const mjModel* m = plant.model();
  const mjtNum* qpos = m->key_qpos + static_cast<ptrdiff_t>(plant.mujoco().keyframe_id(keyframe)) * m->nq;
  std::vector<double> pose(kPoseSize);
  for (size_t i = 0; i < kArmJoints; ++i) pose[i] = qpos[plant.mujoco().joint_qpos_address(kArmJointNames[i])];
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

// qpos addresses of hand_study_joints() in the model
std::vector<int> study_qpos(const hand::HandPlant& plant) {
  std::vector<int> out;
  for (const std::string& name : hand_study_joints()) out.push_back(plant.mujoco().joint_qpos_address(name));
  return out;
}

// the one contact the study means: the index fingertip on the panel
struct ContactPair {
  int tip_geom;
  int panel_geom;
};

bool has_foreign_contact(const mjData* d, const ContactPair& pair) {
  for (int i = 0; i < d->ncon; ++i) {
    const mjContact& c = d->contact[i];
    const bool ours = (c.geom1 == pair.tip_geom && c.geom2 == pair.panel_geom) ||
                      (c.geom1 == pair.panel_geom && c.geom2 == pair.tip_geom);
    if (!ours) return true;
  }
  return false;
}

int steps_per_sample(const HandStudyConfig& c, double timestep_s) {
  const long steps = std::lround(c.sample_period_s / timestep_s);
  if (steps < 1 || std::abs(static_cast<double>(steps) * timestep_s - c.sample_period_s) > 1e-9) {
    throw std::runtime_error(c.file + ": sample_period_s " + std::to_string(c.sample_period_s) +
                             " is no multiple of the model's timestep " + std::to_string(timestep_s));
  }
  return static_cast<int>(steps);
}

// MAD per joint and the force statistics over the recording window
void analyse(const HandStudyConfig& c, HandStudyRunResult& r) {
  const Window window{r.record_begin_s, r.t_s.back()};
  double paper_sum = 0.0;
  for (size_t j = 0; j < r.q_rad.size(); ++j) {
    r.mad_rad.push_back(mean_absolute_deviation_in(r.t_s, r.q_rad[j], c.mad_window, window));
    if (j < kPaperTableJoints) paper_sum += r.mad_rad.back();
    r.mad_max_rad = std::max(r.mad_max_rad, r.mad_rad.back());
  }
  r.mad_paper_average_rad = paper_sum / static_cast<double>(kPaperTableJoints);
  r.tip_force_mean_n = mean_in(r.t_s, r.tip_force_n, window);
  r.tip_force_sd_n = std::sqrt(std::max(0.0, std::pow(rms_in(r.t_s, r.tip_force_n, window), 2) -
                                                 r.tip_force_mean_n * r.tip_force_mean_n));
  r.tip_force_min_n = std::numeric_limits<double>::infinity();
  r.tip_force_max_n = -std::numeric_limits<double>::infinity();
  r.first_contact_s = std::numeric_limits<double>::quiet_NaN();
  for (size_t i = 0; i < r.t_s.size(); ++i) {
    if (r.tip_force_n[i] > 0.0 && std::isnan(r.first_contact_s)) r.first_contact_s = r.t_s[i];
    if (!window.contains(r.t_s[i])) continue;
    r.tip_force_min_n = std::min(r.tip_force_min_n, r.tip_force_n[i]);
    r.tip_force_max_n = std::max(r.tip_force_max_n, r.tip_force_n[i]);
  }
}

}  // namespace

const std::vector<std::string>& hand_study_joints() {
  static const std::vector<std::string> joints = [] {
    // Tables II and III of the paper, in their order
    std::vector<std::string> out = {"Finger_Spread",       "Index_Finger_Distal", "Index_Finger_Proximal",
                                    "Middle_Finger_Distal", "Middle_Finger_Proximal", "Pinky",
                                    "Ring_Finger",          "Thumb_Flexion",       "Thumb_Opposition",
                                    "shoulder_lift_joint",  "shoulder_pan_joint",  "elbow_joint",
                                    "wrist_1_joint",        "wrist_2_joint",       "wrist_3_joint"};
    // then the joints the mechanism moves, which the paper does not list
    for (const std::string_view name : hand::kHandJointNames) {
      if (std::find(hand::kHandMotorNames.begin(), hand::kHandMotorNames.end(), name) == hand::kHandMotorNames.end()) {
        out.emplace_back(name);
      }
    }
    return out;
  }();
  return joints;
}

HandStudyRunResult run_hand_study_case(const HandStudyConfig& c, const HandStudyRun& run) {
  const auto wall_start = std::chrono::steady_clock::now();
  hand::HandPlant plant(sim::MujocoModel::load(c.model_path), hand::HandCoupling::svh());
  if (run.link_inertia_kgm2 > 0.0) plant.set_link_inertia(run.link_inertia_kgm2);
  if (c.hand_torque_limit_nm > 0.0) plant.set_motor_torque_limit(c.hand_torque_limit_nm);
  if (!c.friction_cone.empty()) plant.model()->opt.cone = c.friction_cone == "elliptic" ? mjCONE_ELLIPTIC : mjCONE_PYRAMIDAL;
  if (c.noslip_iterations >= 0) plant.model()->opt.noslip_iterations = c.noslip_iterations;
  hand::MinJerkPath path(keyframe_pose(plant, c.path.front().keyframe));
  for (size_t i = 1; i < c.path.size(); ++i) path.then(keyframe_pose(plant, c.path[i].keyframe), c.path[i].move_s);
  // every PD designed on the inertias at the pose the study holds
  plant.mujoco().reset(c.path.back().keyframe);
  const ArmControl arm = design_arm(plant.mujoco(), c.arm_bandwidth_radps, c.damping_ratio);
  const hand::HandPositionControl hand_control(plant, run.coupling, c.hand_bandwidth_radps, c.damping_ratio,
                                               c.servo_bandwidth_radps);
  plant.mujoco().reset(c.path.front().keyframe);

  const mjModel* m = plant.model();
  mjData* d = plant.data();
  const double dt = m->opt.timestep;
  const int sample_every = steps_per_sample(c, dt);
  const long steps = std::lround((path.duration_s() + c.settle_s + c.record_s) / dt);
  const std::vector<int> qpos = study_qpos(plant);
  const ContactPair tip_on_panel{plant.mujoco().geom_id("svh_index_distal"), plant.mujoco().geom_id("panel")};

  HandStudyRunResult r;
  r.run = run;
  r.record_begin_s = path.duration_s() + c.settle_s;
  r.q_rad.assign(qpos.size(), {});
  std::vector<double> ref(kPoseSize);
  std::vector<double> dref(kPoseSize);
  hand::HandMotorVector m_ref{};
  hand::HandMotorVector dm_ref{};
  for (long step = 0; step < steps; ++step) {
    path.sample(static_cast<double>(step) * dt, ref, dref);
    std::copy(ref.begin() + kArmJoints, ref.end(), m_ref.begin());
    std::copy(dref.begin() + kArmJoints, dref.end(), dm_ref.begin());
    plant.begin_step();
    apply_arm(arm, d, ref, dref);
    hand_control.apply(plant, m_ref, dm_ref);
    plant.end_step();
    r.coupling_residual_max_rad = std::max(r.coupling_residual_max_rad, plant.coupling_residual_rad());
    if (has_foreign_contact(d, tip_on_panel)) ++r.foreign_contact_steps;
    if ((step + 1) % sample_every != 0) continue;
    r.t_s.push_back(static_cast<double>(step + 1) * dt);
    for (size_t j = 0; j < qpos.size(); ++j) r.q_rad[j].push_back(d->qpos[qpos[j]]);
    r.tip_force_n.push_back(plant.tip_force_n());
  }
  r.mujoco_warnings = plant.mujoco_warnings();
  analyse(c, r);
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  return r;
}

}  // namespace teleop::experiment
