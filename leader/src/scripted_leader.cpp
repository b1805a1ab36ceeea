#include "teleop/leader/scripted_leader.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "teleop/common/joint_config.h"
#include "teleop/transport/joint_fields.h"

namespace teleop::leader {

ScriptedLeaderConfig ScriptedLeader::parse_config(const ConfigNode& root) {
  const ConfigNode s = root.child("leader");
  ScriptedLeaderConfig c;
  c.joints = read_joint_count(s);
  c.home_rad = read_joint_list(s, "home_rad", c.joints, Range{-2 * M_PI, 2 * M_PI}, 0.0);
  const double amplitude = s.get_double("amplitude_rad", Range{0, M_PI}, 0.3);
  c.amplitude_rad = read_joint_list(s, "amplitudes_rad", c.joints, Range{0, M_PI}, amplitude);
  c.frequency_hz = s.get_double("frequency_hz", Range{0, 50}, c.frequency_hz);
  c.ramp_s = s.get_double("ramp_s", Range{0, 60}, c.ramp_s);
  c.stiffness_nm_per_rad = s.get_double("stiffness_nm_per_rad", Range{0, 1e5}, c.stiffness_nm_per_rad);
  c.damping_nms_per_rad = s.get_double("damping_nms_per_rad", Range{0, 1e4}, c.damping_nms_per_rad);
  c.peer_timeout_s = s.get_double("peer_timeout_ms", Range{1, 60'000}, 100) * 1e-3;
  c.device = s.get_choice("device", {"scripted", "haptic_arm"}, "scripted") == "haptic_arm"
                 ? ScriptedLeaderConfig::Device::kHapticArm
                 : ScriptedLeaderConfig::Device::kScripted;
  if (auto arm = s.optional_child("haptic_arm")) {
    c.haptic_arm.model.model_path = arm->get_path("model");
    c.haptic_arm.model.keyframe = arm->get_string("keyframe", "");
    c.haptic_arm.hand_stiffness_nm_per_rad = arm->get_double("hand_stiffness_nm_per_rad", Range{0, 1e4}, c.haptic_arm.hand_stiffness_nm_per_rad);
    c.haptic_arm.hand_damping_nms_per_rad = arm->get_double("hand_damping_nms_per_rad", Range{0, 1e3}, c.haptic_arm.hand_damping_nms_per_rad);
  } else if (c.device == ScriptedLeaderConfig::Device::kHapticArm) {
    throw s.error("haptic_arm", "device: haptic_arm needs a haptic_arm section with the model file");
  }
  c.workspace_scale = s.get_double("workspace_scale", Range{0.01, 100}, c.workspace_scale);
  const ConfigNode f = s.child("feedback");
  const std::string source = f.get_choice("source", {"twin", "follower", "none"});
  c.feedback_source = source == "twin"       ? ScriptedLeaderConfig::FeedbackSource::kTwin
                      : source == "follower" ? ScriptedLeaderConfig::FeedbackSource::kFollower
                                             : ScriptedLeaderConfig::FeedbackSource::kNone;
  c.feedback.gain = f.get_double("gain", Range{0, 100}, c.feedback.gain);
  c.feedback.cutoff_hz = f.get_double("cutoff_hz", Range{0, 500}, c.feedback.cutoff_hz);
  c.feedback.max_torque_nm = read_joint_list(f, "max_torque_nm", c.joints, Range{0, 1e3}, 20.0);
  c.feedback.max_rate_nm_per_s = f.get_double("max_rate_nm_per_s", Range{0, 1e6}, c.feedback.max_rate_nm_per_s);
  c.feedback.fade_s = f.get_double("fade_ms", Range{0, 10'000}, c.feedback.fade_s * 1e3) * 1e-3;
  return c;
}

ScriptedLeader::ScriptedLeader(const ScriptedLeaderConfig& config, runtime::NodeContext& context)
    : config_(config),
      period_s_(1.0 / context.node.rate_hz),
      command_(context.participant, transport::topics::kLeaderCommand, context.node.name),
      device_state_(context.participant, transport::topics::kLeaderState, context.node.name),
      follower_state_(context.participant, transport::topics::kFollowerState),
      follower_wrench_(context.participant, transport::topics::kFollowerWrench),
      twin_feedback_(context.participant, transport::topics::kTwinFeedback),
      clutch_(config.joints, config.workspace_scale),
      renderer_(config.joints, config.feedback, context.node.rate_hz) {
  if (config.device == ScriptedLeaderConfig::Device::kHapticArm) {
    HapticArmConfig arm = config.haptic_arm;
    arm.model.period_s = period_s_;
    haptic_arm_ = std::make_unique<SimulatedHapticArm>(arm);
    if (haptic_arm_->joints() != config.joints) throw std::runtime_error("leader.haptic_arm: the model's joint count differs from leader.joints");
  }
  const size_t n = config.joints;
  auto& cmd = command_.sample();
  cmd.robot("leader_device");
  cmd.arm("single");
  cmd.mode().assign(n, msg::CONTROL_JOINT_IMPEDANCE);
  transport::presize(n, cmd.q_des_rad(), cmd.dq_des_radps(), cmd.tau_ff_nm());
  cmd.stiffness_nm_per_rad().assign(n, config.stiffness_nm_per_rad);
  cmd.damping_nms_per_rad().assign(n, config.damping_nms_per_rad);
  auto& st = device_state_.sample();
  st.robot("leader_device");
  st.arm("single");
  transport::presize_joint_state(st, n);
  q_des_ = config.home_rad;
  device_.q_rad = config.home_rad;
  read_device();
  device_home_ = device_.q_rad;
  // the follower's command starts at home: the device's offset from it is not a motion
  clutch_.start(device_.q_rad, config.home_rad);
}

void ScriptedLeader::read_device() {
  if (!haptic_arm_) {
    device_.q_rad = q_des_;
    device_.dq_radps = dq_des_;
    return;
  }
  if (!haptic_arm_->read(device_)) ++device_faults_;
}

void ScriptedLeader::render_feedback(int64_t now_ns) {
  using Source = ScriptedLeaderConfig::FeedbackSource;
  const auto timeout = static_cast<int64_t>(config_.peer_timeout_s * 1e9);
  bool fresh = false;
  if (config_.feedback_source == Source::kTwin) {
    // a sample of the wrong size is ignored (the old feedback stays, then fades when stale)
    fresh = twin_feedback_.age_ns(now_ns) < timeout &&
            transport::read_joints(twin_feedback_.latest().tau_nm(), config_.joints, feedback_);
  } else if (config_.feedback_source == Source::kFollower) {
    // the external torque on the follower acts on the operator's device the same way
    fresh = follower_state_.age_ns(now_ns) < timeout &&
            transport::read_joints(follower_state_.latest().tau_ext_nm(), config_.joints, feedback_);
  }
  // lost or stale source, or the follower gone: fade the feedback out, never cut it
  renderer_.render(feedback_, fresh && state_ == msg::STATE_RUNNING);
}

void ScriptedLeader::operator_motion(double t_s) {
  const double w = 2 * M_PI * config_.frequency_hz;
  // the amplitude fades in (smoothstep over ramp_s), so the motion starts at home without a step
  const double x = config_.ramp_s > 0 ? std::min(1.0, t_s / config_.ramp_s) : 1.0;
  const double envelope = x * x * (3 - 2 * x);
  const double envelope_rate = config_.ramp_s > 0 && x < 1.0 ? 6 * x * (1 - x) / config_.ramp_s : 0.0;
  for (size_t i = 0; i < config_.joints; ++i) {
    // each joint a little out of phase, so that the motion is not degenerate
    const double phase = 0.4 * static_cast<double>(i);
    const double a = config_.amplitude_rad[i];
    q_des_[i] = config_.home_rad[i] + envelope * a * std::sin(w * t_s + phase);
    dq_des_[i] = envelope * a * w * std::cos(w * t_s + phase) + envelope_rate * a * std::sin(w * t_s + phase);
  }
}

void ScriptedLeader::update_state(int64_t now_ns) {
  const bool follower_fresh = follower_state_.age_ns(now_ns) < static_cast<int64_t>(config_.peer_timeout_s * 1e9);
  if (follower_fresh) {
    state_ = msg::STATE_RUNNING;
  } else if (state_ == msg::STATE_RUNNING) {
    // the follower was there and went silent: freeze the command where it is
    state_ = msg::STATE_SAFE_HOLD;
    ++peer_lost_events_;
  }
}

void ScriptedLeader::cycle(const CycleTick& tick) {
  follower_state_.poll();
  follower_wrench_.poll();
  twin_feedback_.poll();
  update_state(tick.now_ns);

  // the operator keeps moving; what the follower is sent freezes while it is lost
  operator_motion(static_cast<double>(tick.index) * period_s_);
  if (haptic_arm_) {
    // the operator moves the device by the script's motion, from where the device started
    for (size_t i = 0; i < config_.joints; ++i) operator_target_[i] = device_home_[i] + q_des_[i] - config_.home_rad[i];
    haptic_arm_->set_operator_target(operator_target_, dq_des_);
  }
  read_device();
  const bool frozen = state_ == msg::STATE_SAFE_HOLD;
  const JointVector& q_cmd = clutch_.map(device_.q_rad, frozen);
  auto& cmd = command_.sample();
  transport::copy_joints(q_cmd, config_.joints, cmd.q_des_rad());
  if (frozen) {
    std::fill(cmd.dq_des_radps().begin(), cmd.dq_des_radps().end(), 0.0);
  } else {
    for (size_t i = 0; i < config_.joints; ++i) cmd.dq_des_radps()[i] = config_.workspace_scale * device_.dq_radps[i];
  }
  command_.publish();

  render_feedback(tick.now_ns);
  if (haptic_arm_ && !haptic_arm_->write(renderer_.output())) ++device_faults_;
  // the device's state in the follower's space (mapped by the clutch): what the twin couples to
  auto& st = device_state_.sample();
  transport::copy_joints(q_cmd, config_.joints, st.q_rad());
  std::copy(cmd.dq_des_radps().begin(), cmd.dq_des_radps().end(), st.dq_radps().begin());
  transport::copy_joints(renderer_.output(), config_.joints, st.tau_measured_nm());
  device_state_.publish();
}

void ScriptedLeader::active_faults(std::vector<uint32_t>& faults) const {
  if (state_ == msg::STATE_SAFE_HOLD) faults.push_back(msg::FAULT_PEER_LOST);
}

void ScriptedLeader::fill_report(runtime::NodeReport& report) const {
  report.add(command_);
  report.add(device_state_);
  report.add(follower_state_);
  report.add(follower_wrench_);
  report.add(twin_feedback_);
  report.counters.emplace_back("peer_lost_events", static_cast<double>(peer_lost_events_));
  report.counters.emplace_back("device_faults", static_cast<double>(device_faults_));
  report.counters.emplace_back("feedback_peak_nm", renderer_.peak_nm());
  report.counters.emplace_back("feedback_saturations", static_cast<double>(renderer_.saturations()));
  report.counters.emplace_back("feedback_rate_limited", static_cast<double>(renderer_.rate_limited()));
}

}  // namespace teleop::leader
