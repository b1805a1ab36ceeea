#include "teleop/follower/follower_config.h"

#include <cmath>
#include <limits>

#include "calibration_file.h"
#include "teleop/common/joint_config.h"
#include "teleop/control/types.h"
#include "teleop/runtime/arm_configs.h"
#include "teleop/sim/model_config.h"

namespace teleop::follower {
namespace {

control::JointVector to_eigen(const JointVector& v) { return Eigen::Map<const control::JointVector>(v.data()); }

void read_joint_limits(const ConfigNode& s, size_t n, JointLimits& l) {
  // unset: the robot's own (its model's ranges and motor limits; limits_in_force.h)
  constexpr double kRobots = std::numeric_limits<double>::infinity();
  l.q_min_rad = read_joint_list(s, "q_min_rad", n, kJointAngleRange, -kRobots);
  l.q_max_rad = read_joint_list(s, "q_max_rad", n, kJointAngleRange, kRobots);
  for (size_t i = 0; i < n; ++i) {
    if (l.q_min_rad[i] >= l.q_max_rad[i]) throw s.error("q_max_rad", "must exceed q_min_rad for every joint");
  }
  l.max_velocity_radps = s.get_double("max_velocity_radps", Range{0.01, 100}, l.max_velocity_radps);
  l.max_torque_nm = read_joint_list(s, "max_torque_nm", n, Range{0.1, 1e4}, kRobots);
  l.max_stiffness_nm_per_rad = s.get_double("max_stiffness_nm_per_rad", Range{0, 1e6}, l.max_stiffness_nm_per_rad);
  l.max_damping_nms_per_rad = s.get_double("max_damping_nms_per_rad", Range{0, 1e5}, l.max_damping_nms_per_rad);
  l.max_command_age_s = s.get_bound_or_off("max_command_age_ms", Range{1, 60'000}, l.max_command_age_s * 1e3) * 1e-3;
}

void read_cartesian_limits(const ConfigNode& s, JointLimits& l) {
  l.workspace_min_m = read_vector3(s, "workspace_min_m", Range{-10, 10}, l.workspace_min_m);
  l.workspace_max_m = read_vector3(s, "workspace_max_m", Range{-10, 10}, l.workspace_max_m);
  for (size_t i = 0; i < 3; ++i) {
    if (l.workspace_min_m[i] >= l.workspace_max_m[i]) throw s.error("workspace_max_m", "must exceed workspace_min_m on every axis");
  }
  l.max_translational_stiffness_n_per_m =
      s.get_double("max_translational_stiffness_n_per_m", Range{0, 1e5}, l.max_translational_stiffness_n_per_m);
  l.max_rotational_stiffness_nm_per_rad =
      s.get_double("max_rotational_stiffness_nm_per_rad", Range{0, 1e4}, l.max_rotational_stiffness_nm_per_rad);
  l.max_nullspace_stiffness_nm_per_rad =
      s.get_double("max_nullspace_stiffness_nm_per_rad", Range{0, 1e4}, l.max_nullspace_stiffness_nm_per_rad);
  l.max_linear_velocity_mps = s.get_double("max_linear_velocity_mps", Range{0.001, 10}, l.max_linear_velocity_mps);
  l.max_angular_velocity_radps = s.get_double("max_angular_velocity_radps", Range{0.001, 20}, l.max_angular_velocity_radps);
}

// `reflex: off`, or a mapping of thresholds (safety_reflex.h); absent: the Panda's own
SafetyReflexConfig read_reflex(const ConfigNode& s, size_t n) {
  SafetyReflexConfig r;
  if (!s.has("reflex")) return r;
  if (s.get_yaml("reflex") == "off") {
    r.enabled = false;
    return r;
  }
  const ConfigNode c = s.child("reflex");
  const auto per_joint = [&](const char* key, Range range, const JointVector& fallback) {
    return c.has(key) ? read_joint_list(c, key, n, range, 0.0) : fallback;
  };
  r.joint_torque_nm = per_joint("joint_torque_nm", Range{0.1, 1e4}, r.joint_torque_nm);
  r.joint_velocity_radps = per_joint("joint_velocity_radps", Range{0.01, 100}, r.joint_velocity_radps);
  r.force_n = read_vector3(c, "force_n", Range{0.1, 1e5}, r.force_n);
  r.torque_nm = read_vector3(c, "torque_nm", Range{0.1, 1e4}, r.torque_nm);
  r.hold_stiffness_nm_per_rad = c.get_double("hold_stiffness_nm_per_rad", Range{0, 1e4}, r.hold_stiffness_nm_per_rad);
  r.hold_damping_nms_per_rad = c.get_double("hold_damping_nms_per_rad", Range{0, 1e3}, r.hold_damping_nms_per_rad);
  r.brake_share_per_cycle = c.get_double("brake_share_per_cycle", Range{0, 0.5}, r.brake_share_per_cycle);
  return r;
}

// `per_arm`: the arms name their models (follower.arms, follower_arms.cpp)
ArmControlConfig read_control(const ConfigNode& c, size_t n, bool per_arm) {
  ArmControlConfig a;
  if (!per_arm || c.has("model")) a.model_path = sim::get_model_path(c, "model");
  a.ee_site = c.get_string("ee_site", a.ee_site);
  a.position_pd.kp = to_eigen(read_joint_list(c, "position_pd_kp", n, Range{0, 1e5}, 600.0));
  a.position_pd.kd = to_eigen(read_joint_list(c, "position_pd_kd", n, Range{0, 1e4}, 30.0));
  a.nullspace_damping = to_eigen(read_joint_list(c, "nullspace_damping_nms_per_rad", n, Range{0, 1e3}, 2.0));
  a.rest_posture_rad = to_eigen(read_joint_list(c, "rest_posture_rad", n, kJointAngleRange, 0.0));
  a.blend_s = c.get_double("blend_ms", Range{0, 5000}, a.blend_s * 1e3) * 1e-3;
  a.observer_gain_per_s = c.get_double("observer_gain_per_s", Range{1, 1000}, a.observer_gain_per_s);
  const std::string source =
      c.get_choice("published_estimate", {"momentum_observer", "direct", "hardware"}, "momentum_observer");
  a.published_estimate = source == "direct"     ? ExternalTorqueSource::kDirect
                         : source == "hardware" ? ExternalTorqueSource::kHardware
                                                : ExternalTorqueSource::kMomentumObserver;
  return a;
}


// an arm's own keys on top of the shared `follower:` section
FollowerConfig arm_config(const FollowerConfig& shared, const std::string& name, const ConfigNode& a) {
  FollowerConfig c = shared;
  c.arm = name;
  // the arms share one simulated scene: only the simulation has several arms today
  if (std::dynamic_pointer_cast<const robot::MujocoHardwareSpec>(shared.hardware) == nullptr) {
    throw a.error("joint_prefix", std::string("follower.arms needs the mujoco hardware, not ") + shared.hardware->backend());
  }
  c.joint_prefix = a.get_string("joint_prefix");
  c.ee_site = a.get_string("ee_site");
  c.control.model_path = sim::get_model_path(a, "control_model");
  c.control.ee_site = c.ee_site;
  if (a.has("rest_posture_rad")) {
    const JointVector rest = read_joint_list(a, "rest_posture_rad", c.joints, kJointAngleRange, 0.0);
    c.control.rest_posture_rad = Eigen::Map<const control::JointVector>(rest.data());
  }
  return c;
}

}  // namespace

FollowerConfig parse_follower_config(const ConfigNode& root, const robot::HardwareRegistry& hardware,
                                     CalibrationUse calibration) {
  const ConfigNode s = root.child("follower");
  FollowerConfig c;
  c.joints = read_joint_count(s);
  if (c.joints != static_cast<size_t>(control::kDof)) {
    throw s.error("joints", "the follower drives a " + std::to_string(control::kDof) + "-joint arm");
  }
  c.hardware = hardware.parse(s);
  c.command_source = s.get_choice("command_source", {"leader", "twin"}, "leader") == "twin"
                         ? FollowerConfig::CommandSource::kTwin
                         : FollowerConfig::CommandSource::kLeader;
  c.teleoperation = runtime::parse_teleoperation_config(root);
  if (c.teleoperation) {
    // model-mediated: the follower tracks the twin; every other architecture: the leader
    const bool mmt = c.teleoperation->architecture->commands == runtime::CommandPath::kTwin;
    const auto implied = mmt ? FollowerConfig::CommandSource::kTwin : FollowerConfig::CommandSource::kLeader;
    if (s.has("command_source") && c.command_source != implied) {
      throw s.error("command_source", std::string("contradicts teleoperation.architecture ") +
                                          std::string(c.teleoperation->architecture->name) + " (leave it out)");
    }
    c.command_source = implied;
  }
  if (s.has("accept_commands_from")) {
    c.accept_commands_from = s.get_string_list("accept_commands_from");
    if (c.accept_commands_from.empty()) throw s.error("accept_commands_from", "names no node (leave it out to accept any)");
  }
  read_joint_limits(s, c.joints, c.limits);
  read_cartesian_limits(s, c.limits);
  c.max_torque_rate_nm_per_s = s.get_bound_or_off("max_torque_rate_nm_per_s", Range{1, 1e6}, c.max_torque_rate_nm_per_s);
  c.command_timeout_s = s.get_double("command_timeout_ms", Range{1, 60'000}, c.command_timeout_s * 1e3) * 1e-3;
  c.rejoin_speed_radps = s.get_double("rejoin_speed_radps", Range{0.01, 10}, c.rejoin_speed_radps);
  c.enable_after_hold = s.get_choice("after_hold", {"resume", "enable"}, "resume") == "enable";
  c.hold_stiffness_nm_per_rad = s.get_double("hold_stiffness_nm_per_rad", Range{0, 1e5}, c.hold_stiffness_nm_per_rad);
  c.hold_damping_nms_per_rad = s.get_double("hold_damping_nms_per_rad", Range{0, 1e4}, c.hold_damping_nms_per_rad);
  c.control = read_control(s.child("control"), c.joints, s.has("arms"));
  if (const auto section = s.optional_child("calibration")) {
    c.calibration_file = calibration_file_of(*section);
    c.calibration_plan = read_calibration_plan(*section);
    if (calibration == CalibrationUse::kApply && !c.calibration_file.empty()) {
      c.control.calibration = applied_calibration(*section, c.calibration_file);
    }
  }
  c.reflex = read_reflex(s, c.joints);
  if (s.has("tracked_objects")) {
    if (!s.has("arms")) throw s.error("tracked_objects", "needs the shared scene of follower.arms");
    c.tracked_objects.bodies = s.get_string_list("tracked_objects");
    c.tracked_objects.rate_hz = s.get_double("tracked_object_rate_hz", Range{1, 1000}, c.tracked_objects.rate_hz);
  }
  return c;
}

std::vector<FollowerConfig> parse_follower_arms(const ConfigNode& root, const robot::HardwareRegistry& hardware) {
  return runtime::read_arm_configs(root.child("follower"), parse_follower_config(root, hardware), arm_config);
}

}  // namespace teleop::follower
