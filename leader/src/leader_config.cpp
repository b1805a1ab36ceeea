#include "leader_config.h"

#include <cmath>

#include "teleop/common/joint_config.h"
#include "teleop/runtime/arm_configs.h"
#include "teleop/sim/model_config.h"

namespace teleop::leader {
namespace {

using runtime::Architecture;

CartesianGains parse_cartesian(const ConfigNode& s) {
  CartesianGains g;
  const auto c = s.optional_child("cartesian");
  if (!c) return g;
  g.translational_n_per_m = read_vector3(*c, "stiffness_n_per_m", Range{0, 1e5}, g.translational_n_per_m);
  g.rotational_nm_per_rad = read_vector3(*c, "stiffness_nm_per_rad", Range{0, 1e4}, g.rotational_nm_per_rad);
  g.damping_ratio = c->get_double("damping_ratio", Range{0, 10}, g.damping_ratio);
  g.nullspace_stiffness_nm_per_rad = c->get_double("nullspace_stiffness_nm_per_rad", Range{0, 1e3}, g.nullspace_stiffness_nm_per_rad);
  return g;
}

}  // namespace

std::shared_ptr<const JointTrajectory> load_recording(const ConfigNode& section, const std::string& key,
                                                     const OperatorMotionConfig& motion) {
  return std::make_shared<const JointTrajectory>(
      JointTrajectory::load_csv(section.get_path(key), motion.joints, motion.recording_columns));
}

namespace {

OperatorMotionConfig parse_motion(const ConfigNode& s, size_t joints, const JointVector& home) {
  OperatorMotionConfig m;
  m.joints = joints;
  m.home_rad = home;
  const std::string kind = s.get_choice("motion", {"sine", "push_hold", "recorded"}, "sine");
  m.kind = kind == "push_hold" ? OperatorMotionConfig::Kind::kPushHold
           : kind == "recorded" ? OperatorMotionConfig::Kind::kRecorded
                                : OperatorMotionConfig::Kind::kSine;
  if (m.kind == OperatorMotionConfig::Kind::kRecorded) {
    // a CSV with t_s and <columns>0..: e.g. an earlier leader trace (columns q_dev_); each arm of
    // a two-handed station may give its own file (leader_arms.cpp)
    const auto recording = s.child("recording");
    m.recording_columns = recording.get_string("columns", m.recording_columns);
    if (!s.has("arms") || recording.has("file")) m.recording = load_recording(recording, "file", m);
  }
  const double amplitude = s.get_double("amplitude_rad", Range{0, M_PI}, 0.3);
  m.amplitude_rad = read_joint_list(s, "amplitudes_rad", joints, Range{-M_PI, M_PI}, amplitude);
  m.frequency_hz = s.get_double("frequency_hz", Range{0, 50}, m.frequency_hz);
  m.ramp_s = s.get_double("ramp_s", Range{0, 60}, m.ramp_s);
  m.let_go_at_s = s.get_double("let_go_at_s", Range{0, 1e6}, m.let_go_at_s);
  m.starts_in_command = s.get_choice("motion_starts", {"at_start", "in_command"}, "at_start") == "in_command";
  for (const ConfigNode& p : s.get_node_list("button_presses")) {
    m.presses.push_back({static_cast<uint32_t>(p.get_int("button", Range{0, kMaxButton})), p.get_double("at_s", Range{0, 1e6}),
                         p.get_double("hold_s", Range{1e-3, 1e6}, 0.2)});
  }
  return m;
}

// what the device's buttons do; -1: no button does it
StopButtons parse_stop_buttons(const ConfigNode& s) {
  StopButtons b;
  const auto buttons = s.optional_child("buttons");
  if (!buttons) return b;
  b.emergency_stop = static_cast<int>(buttons->get_int("emergency_stop", Range{-1, kMaxButton}, -1));
  b.enable = static_cast<int>(buttons->get_int("enable", Range{-1, kMaxButton}, -1));
  if (b.enable >= 0 && b.enable == b.emergency_stop) {
    throw buttons->error("enable", "is the emergency stop's button too: an enable must be a deliberate other act");
  }
  b.dead_man = static_cast<int>(buttons->get_int("dead_man", Range{-1, kMaxButton}, -1));
  b.clutch = static_cast<int>(buttons->get_int("clutch", Range{-1, kMaxButton}, -1));
  if (b.clutch >= 0 && b.clutch == b.dead_man) throw buttons->error("clutch", "is the dead-man button too");
  for (const int stop : {b.emergency_stop, b.enable}) {
    if (stop >= 0 && (stop == b.dead_man || stop == b.clutch)) {
      throw buttons->error(stop == b.dead_man ? "dead_man" : "clutch", "is a button of the stop chain too");
    }
  }
  return b;
}

std::optional<WorkspaceBox> parse_workspace_box(const ConfigNode& s) {
  const auto box = s.optional_child("workspace_box_m");
  if (!box) return std::nullopt;
  WorkspaceBox b;
  const std::vector<double> min = box->get_double_list("min", Range{-10, 10});
  const std::vector<double> max = box->get_double_list("max", Range{-10, 10});
  if (min.size() != 3) throw box->error("min", "needs 3 values (x, y, z in the base frame)");
  if (max.size() != 3) throw box->error("max", "needs 3 values (x, y, z in the base frame)");
  for (size_t i = 0; i < 3; ++i) {
    if (!(min[i] < max[i])) throw box->error("max", "must exceed min in every axis");
    b.min_m[i] = min[i];
    b.max_m[i] = max[i];
  }
  return b;
}

void parse_feedback(const ConfigNode& s, LeaderConfig& c) {
  const ConfigNode f = s.child("feedback");
  c.feedback_enabled = f.get_bool("enabled", true);
  c.feedback.gain = f.get_double("gain", Range{0, 100}, c.feedback.gain);
  c.feedback.cutoff_hz = f.get_double("cutoff_hz", Range{0, 500}, c.feedback.cutoff_hz);
  c.feedback.max_torque_nm = read_joint_list(f, "max_torque_nm", c.joints, Range{0, 1e3}, 20.0);
  c.feedback.max_rate_nm_per_s = f.get_bound_or_off("max_rate_nm_per_s", Range{1, 1e6}, c.feedback.max_rate_nm_per_s);
  c.feedback.fade_s = f.get_double("fade_ms", Range{0, 10'000}, c.feedback.fade_s * 1e3) * 1e-3;
  c.feedback.hands_off_fade_s =
      f.get_double("hands_off_fade_ms", Range{0, 10'000}, c.feedback.hands_off_fade_s * 1e3) * 1e-3;
  c.hands_off.speed_mps = f.get_bound_or_off("hands_off_speed_mps", Range{0.01, 10}, c.hands_off.speed_mps);
  c.hands_off.resume_s = f.get_double("hands_off_resume_ms", Range{0, 60'000}, c.hands_off.resume_s * 1e3) * 1e-3;
  if (std::isfinite(c.hands_off.speed_mps) && c.arm_model.empty() && !c.device->cartesian() && !s.has("arms")) {
    throw f.error("hands_off_speed_mps", "needs the device's flange speed: give leader.arm_model");
  }
}

}  // namespace

LeaderConfig parse_leader_config(const ConfigNode& root, const DeviceRegistry& devices) {
  const ConfigNode s = root.child("leader");
  LeaderConfig c;
  c.joints = read_joint_count(s);
  c.home_rad = read_joint_list(s, "home_rad", c.joints, kJointAngleRange, 0.0);
  c.motion = parse_motion(s, c.joints, c.home_rad);
  c.stiffness_nm_per_rad = s.get_double("stiffness_nm_per_rad", Range{0, 1e5}, c.stiffness_nm_per_rad);
  c.damping_nms_per_rad = s.get_double("damping_nms_per_rad", Range{0, 1e4}, c.damping_nms_per_rad);
  c.cartesian = parse_cartesian(s);
  c.peer_timeout_s = s.get_double("peer_timeout_ms", Range{1, 60'000}, 100) * 1e-3;
  c.device = devices.parse(s);
  // a two-handed station names each hand's model in leader.arms (leader_arms.cpp)
  const bool per_arm_models = s.has("arms");
  if (s.has("arm_model")) c.arm_model = sim::get_model_path(s, "arm_model");
  c.ee_site = s.get_string("ee_site", c.ee_site);
  c.workspace_scale = s.get_double("workspace_scale", Range{0.01, 100}, c.workspace_scale);
  c.workspace_box = parse_workspace_box(s);
  if (const auto hand = s.optional_child("hand")) {
    try {
      c.hand = parse_hand_plan(*hand);
    } catch (const std::invalid_argument& e) {
      throw hand->error("plan", e.what());
    }
  }
  parse_feedback(s, c);
  c.stop_buttons = parse_stop_buttons(s);
  c.button_input = parse_button_input(s);
  const auto teleoperation = runtime::parse_teleoperation_config(root);
  if (!teleoperation) throw root.error("teleoperation", "the leader needs a teleoperation section (architecture)");
  c.teleoperation = *teleoperation;
  const std::string architecture(c.teleoperation.architecture->name);
  if (c.device->cartesian() && !runtime::is_cartesian(*c.teleoperation.architecture)) {
    throw s.error("device", std::string(c.device->device()) + " moves a Cartesian pose, it has no joints: architecture " +
                                architecture + " commands joint positions; use pfc or pfc_tdpa");
  }
  if (runtime::is_cartesian(*c.teleoperation.architecture) && c.arm_model.empty() && !per_arm_models) {
    throw s.error("arm_model", std::string("architecture ") + std::string(c.teleoperation.architecture->name) +
                                   " maps the device in Cartesian space: give the arm's model file");
  }
  return c;
}

namespace {

// a hand's own keys on top of the shared `leader:` section
LeaderConfig arm_config(const LeaderConfig& shared, const std::string& name, const ConfigNode& a) {
  LeaderConfig c = shared;
  c.arm = name;
  // the hand's device is mounted like the robot's arm: one model for the device and the mapping
  c.arm_model = sim::get_model_path(a, "model");
  c.ee_site = a.get_string("ee_site");
  c.home_rad = read_joint_list(a, "home_rad", c.joints, kJointAngleRange, 0.0);
  c.motion.home_rad = c.home_rad;
  if (c.motion.kind == OperatorMotionConfig::Kind::kRecorded) {
    c.motion.recording = load_recording(a, "recording", c.motion);
  } else if (a.has("recording")) {
    throw a.error("recording", "only for leader.motion: recorded");
  }
  return c;
}

}  // namespace

std::vector<LeaderConfig> parse_leader_arms(const ConfigNode& root, const DeviceRegistry& devices) {
  return runtime::read_arm_configs(root.child("leader"), parse_leader_config(root, devices), arm_config);
}

}  // namespace teleop::leader
