#include "teleop/leader/scripted_leader.h"

#include <algorithm>
#include <cmath>

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
  return c;
}

ScriptedLeader::ScriptedLeader(const ScriptedLeaderConfig& config, runtime::NodeContext& context)
    : config_(config),
      period_s_(1.0 / context.node.rate_hz),
      command_(context.participant, transport::topics::kLeaderCommand, context.node.name),
      device_state_(context.participant, transport::topics::kLeaderState, context.node.name),
      follower_state_(context.participant, transport::topics::kFollowerState),
      follower_wrench_(context.participant, transport::topics::kFollowerWrench),
      twin_feedback_(context.participant, transport::topics::kTwinFeedback) {
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

  if (state_ == msg::STATE_SAFE_HOLD) {
    dq_des_.fill(0.0);
  } else {
    operator_motion(static_cast<double>(tick.index) * period_s_);
  }
  auto& cmd = command_.sample();
  transport::copy_joints(q_des_, config_.joints, cmd.q_des_rad());
  transport::copy_joints(dq_des_, config_.joints, cmd.dq_des_radps());
  command_.publish();

  auto& st = device_state_.sample();
  transport::copy_joints(q_des_, config_.joints, st.q_rad());
  transport::copy_joints(dq_des_, config_.joints, st.dq_radps());
  // the torque the device renders is the twin's feedback (a mismatched sample is ignored)
  if (twin_feedback_.has_sample() && transport::read_joints(twin_feedback_.latest().tau_nm(), config_.joints, feedback_)) {
    transport::copy_joints(feedback_, config_.joints, st.tau_measured_nm());
  }
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
}

}  // namespace teleop::leader
