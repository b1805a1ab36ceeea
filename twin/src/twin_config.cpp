#include "twin_config.h"

#include <cmath>

#include "teleop/common/joint_config.h"
#include "teleop/runtime/arm_configs.h"
#include "teleop/runtime/architecture.h"

namespace teleop::twin {
namespace {

LockstepConfig read_lockstep(const ConfigNode& s) {
  LockstepConfig c;
  c.timeout_s = s.get_double("timeout_ms", Range{1, 600'000}, c.timeout_s * 1e3) * 1e-3;
  c.steps = static_cast<uint64_t>(s.get_int("steps", Range{0, 1e9}, 0));
  c.trajectory_file = s.get_string("trajectory_file", "");
  return c;
}

HilConfig read_hil(const ConfigNode& s) {
  HilConfig c;
  const std::vector<double> goal = s.get_double_list("goal_rad", kJointAngleRange);
  if (goal.empty() || goal.size() > kMaxJoints) throw s.error("goal_rad", "expected one angle per driven joint");
  std::copy(goal.begin(), goal.end(), c.goal_rad.begin());
  c.goal_joints = goal.size();
  c.move_time_s = s.get_double("move_time_s", Range{0.01, 600}, c.move_time_s);
  c.stiffness_nm_per_rad = s.get_double("stiffness_nm_per_rad", Range{0, 1e5}, c.stiffness_nm_per_rad);
  c.damping_nms_per_rad = s.get_double("damping_nms_per_rad", Range{0, 1e4}, c.damping_nms_per_rad);
  const std::string topic = s.get_choice("command_topic", {"twin", "leader"}, "twin");
  c.command_topic = topic == "leader" ? HilConfig::CommandTopic::kLeader : HilConfig::CommandTopic::kTwin;
  c.peer_timeout_s = s.get_double("peer_timeout_ms", Range{1, 60'000}, 100) * 1e-3;
  return c;
}

CorrectionConfig read_correction(const ConfigNode& s) {
  CorrectionConfig c;
  c.geom = s.get_string("geom");
  if (s.has("probe")) c.probe = read_side(s, "probe");
  c.normal = read_direction(s, "normal");
  c.contact_force_n = s.get_double("contact_force_n", Range{0.01, 1e4}, c.contact_force_n);
  c.free_force_n = s.get_double("free_force_n", Range{0, 1e4}, c.free_force_n);
  if (c.free_force_n > c.contact_force_n) throw s.error("free_force_n", "must not exceed contact_force_n");
  c.free_margin_m = s.get_double("free_margin_m", Range{0, 0.1}, c.free_margin_m);
  c.rate_m_per_s = s.get_double("rate_m_per_s", Range{1e-6, 1}, c.rate_m_per_s);
  c.max_offset_m = s.get_double("max_offset_m", Range{0, 1}, c.max_offset_m);
  c.timeout_s = s.get_double("timeout_ms", Range{1, 60'000}, c.timeout_s * 1e3) * 1e-3;
  c.max_skew_s = s.get_double("max_skew_ms", Range{0, 1000}, c.max_skew_s * 1e3) * 1e-3;
  return c;
}

ObjectCorrectionConfig read_object_correction(const ConfigNode& s) {
  ObjectCorrectionConfig c;
  c.bodies = s.get_string_list("bodies");
  if (c.bodies.empty()) throw s.error("bodies", "names no body to correct");
  c.stiffness_n_per_m = s.get_double("stiffness_n_per_m", Range{0, 1e5}, c.stiffness_n_per_m);
  c.damping_ns_per_m = s.get_double("damping_ns_per_m", Range{0, 1e4}, c.damping_ns_per_m);
  c.stiffness_nm_per_rad = s.get_double("stiffness_nm_per_rad", Range{0, 1e4}, c.stiffness_nm_per_rad);
  c.damping_nms_per_rad = s.get_double("damping_nms_per_rad", Range{0, 1e3}, c.damping_nms_per_rad);
  c.max_force_n = s.get_double("max_force_n", Range{0, 1e4}, c.max_force_n);
  c.max_torque_nm = s.get_double("max_torque_nm", Range{0, 1e3}, c.max_torque_nm);
  c.timeout_s = s.get_double("timeout_ms", Range{1, 60'000}, c.timeout_s * 1e3) * 1e-3;
  return c;
}

}  // namespace

TwinConfig parse_twin_config(const ConfigNode& root) {
  const ConfigNode s = root.child("twin");
  TwinConfig c;
  const std::string mode = s.get_choice("mode", {"realtime", "lockstep", "hil"}, "realtime");
  c.mode = mode == "lockstep" ? TwinMode::kLockstep : (mode == "hil" ? TwinMode::kHil : TwinMode::kRealtime);
  c.joints = read_joint_count(s);
  c.model = read_twin_model_config(s.child("model"));
  const std::string coupled = s.get_choice("coupled_to", {"leader", "follower"}, "leader");
  c.coupled_to = coupled == "follower" ? TwinConfig::CoupledTo::kFollower : TwinConfig::CoupledTo::kLeader;
  c.feedback_gain = s.get_double("feedback_gain", Range{0, 10}, c.feedback_gain);
  c.feedback_cutoff_hz = s.get_double("feedback_cutoff_hz", Range{0, 1e4}, c.feedback_cutoff_hz);
  c.peer_timeout_s = s.get_double("peer_timeout_ms", Range{1, 60'000}, 100) * 1e-3;
  c.rejoin_speed_radps = s.get_double("rejoin_speed_radps", Range{0.01, 10}, c.rejoin_speed_radps);
  if (auto lockstep = s.optional_child("lockstep")) c.lockstep = read_lockstep(*lockstep);
  if (auto hil = s.optional_child("hil")) c.hil = read_hil(*hil);
  if (c.mode == TwinMode::kHil && !s.has("hil")) throw s.error("hil", "mode: hil needs a hil section with the goal");
  const auto teleoperation = runtime::parse_teleoperation_config(root);
  c.mmt.enabled = teleoperation && teleoperation->architecture->commands == runtime::CommandPath::kTwin;
  if (auto mmt = s.optional_child("mmt")) {
    c.mmt.stiffness_nm_per_rad = mmt->get_double("follower_stiffness_nm_per_rad", Range{0, 1e5}, c.mmt.stiffness_nm_per_rad);
    c.mmt.damping_nms_per_rad = mmt->get_double("follower_damping_nms_per_rad", Range{0, 1e4}, c.mmt.damping_nms_per_rad);
    if (auto correction = mmt->optional_child("correction")) c.mmt.correction = read_correction(*correction);
  }
  if (auto objects = s.optional_child("object_correction")) c.object_correction = read_object_correction(*objects);
  if (c.mmt.enabled && (c.mode != TwinMode::kRealtime || c.coupled_to != TwinConfig::CoupledTo::kLeader)) {
    throw s.error("mode", "teleoperation.architecture mmt needs mode: realtime and coupled_to: leader");
  }
  return c;
}

namespace {

// an arm's own keys on top of the shared `twin:` section
TwinConfig arm_config(const TwinConfig& shared, const std::string& name, const ConfigNode& a) {
  TwinConfig c = shared;
  c.arm = name;
  c.joint_prefix = a.get_string("joint_prefix");
  if (c.joint_prefix.empty()) throw a.error("joint_prefix", "must not be empty: it tells this arm's joints from the others'");
  return c;
}

// what only the one-arm twin does
void refuse_one_arm_features(const ConfigNode& section, const TwinConfig& shared) {
  if (shared.mode != TwinMode::kRealtime) {
    throw section.error("arms", "mode: lockstep and mode: hil run one arm only; a twin with arms runs mode: realtime");
  }
  if (shared.mmt.correction) {
    throw section.child("mmt").error("correction", "model correction runs on one arm only, not with twin.arms");
  }
}

}  // namespace

std::vector<TwinConfig> parse_twin_arms(const ConfigNode& root) {
  const ConfigNode section = root.child("twin");
  const TwinConfig shared = parse_twin_config(root);
  if (section.has("arms")) refuse_one_arm_features(section, shared);
  if (!section.has("arms") && shared.object_correction) {
    throw section.error("object_correction", "corrects the shared objects of a twin with arms (twin.arms) only");
  }
  return runtime::read_arm_configs(section, shared, arm_config);
}

}  // namespace teleop::twin
