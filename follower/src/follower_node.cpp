#include "teleop/follower/follower_node.h"

#include <algorithm>
#include <cmath>

#include "teleop/common/joint_config.h"
#include "teleop/transport/joint_fields.h"

namespace teleop::follower {
FollowerConfig FollowerNode::parse_config(const ConfigNode& root) {
  const ConfigNode s = root.child("follower");
  FollowerConfig c;
  const size_t n = read_joint_count(s);
  c.model = read_joint_model(s.child("model"), n);
  c.home_rad = read_joint_list(s, "home_rad", n, Range{-2 * M_PI, 2 * M_PI}, 0.0);
  c.limits.q_min_rad = read_joint_list(s, "q_min_rad", n, Range{-2 * M_PI, 2 * M_PI}, -2.8);
  c.limits.q_max_rad = read_joint_list(s, "q_max_rad", n, Range{-2 * M_PI, 2 * M_PI}, 2.8);
  for (size_t i = 0; i < n; ++i) {
    if (c.limits.q_min_rad[i] >= c.limits.q_max_rad[i]) throw s.error("q_max_rad", "must exceed q_min_rad for every joint");
  }
  c.limits.max_velocity_radps = s.get_double("max_velocity_radps", Range{0.01, 100}, c.limits.max_velocity_radps);
  c.limits.max_torque_nm = s.get_double("max_torque_nm", Range{0.1, 1e4}, c.limits.max_torque_nm);
  c.limits.max_stiffness_nm_per_rad =
      s.get_double("max_stiffness_nm_per_rad", Range{0, 1e6}, c.limits.max_stiffness_nm_per_rad);
  c.limits.max_damping_nms_per_rad = s.get_double("max_damping_nms_per_rad", Range{0, 1e5}, c.limits.max_damping_nms_per_rad);
  c.command_timeout_s = s.get_double("command_timeout_ms", Range{1, 60'000}, 20) * 1e-3;
  c.hold_stiffness_nm_per_rad = s.get_double("hold_stiffness_nm_per_rad", Range{0, 1e5}, c.hold_stiffness_nm_per_rad);
  c.hold_damping_nms_per_rad = s.get_double("hold_damping_nms_per_rad", Range{0, 1e4}, c.hold_damping_nms_per_rad);
  c.wrench_lever_m = s.get_double("wrench_lever_m", Range{0.01, 10}, c.wrench_lever_m);
  return c;
}

FollowerNode::FollowerNode(const FollowerConfig& config, runtime::NodeContext& context)
    : config_(config),
      period_s_(1.0 / context.node.rate_hz),
      model_(config.model),
      validator_(config.model.joints, config.limits),
      command_(context.participant, transport::topics::kLeaderCommand),
      state_pub_(context.participant, transport::topics::kFollowerState, context.node.name),
      wrench_pub_(context.participant, transport::topics::kFollowerWrench, context.node.name) {
  model_.reset(config.home_rad);
  auto& st = state_pub_.sample();
  st.robot("follower_sim");
  st.arm("single");
  transport::presize(config.model.joints, st.q_rad(), st.dq_radps(), st.tau_measured_nm(), st.tau_ext_nm());
  wrench_pub_.sample().frame("tool");
  // until a command arrives, hold the home pose
  active_.q_des_rad = config.home_rad;
  active_.stiffness.fill(config.hold_stiffness_nm_per_rad);
  active_.damping.fill(config.hold_damping_nms_per_rad);
}

void FollowerNode::take_command(int64_t now_ns) {
  if (command_.poll() == 0) return;
  if (validator_.validate(command_.latest(), active_) == CommandVerdict::kRejected) return;
  last_valid_command_ns_ = now_ns;
  have_command_ = true;
}

void FollowerNode::run_watchdog(int64_t now_ns) {
  const bool fresh = have_command_ && now_ns - last_valid_command_ns_ < static_cast<int64_t>(config_.command_timeout_s * 1e9);
  if (fresh) {
    state_ = msg::STATE_RUNNING;
    return;
  }
  if (state_ == msg::STATE_RUNNING) {
    // commands stopped: hold the pose we are at, softly, until they come back
    state_ = msg::STATE_SAFE_HOLD;
    ++watchdog_trips_;
    std::copy_n(model_.q().begin(), config_.model.joints, active_.q_des_rad.begin());
    active_.dq_des_radps.fill(0.0);
    active_.tau_ff_nm.fill(0.0);
    active_.stiffness.fill(config_.hold_stiffness_nm_per_rad);
    active_.damping.fill(config_.hold_damping_nms_per_rad);
  }
}

void FollowerNode::compute_torque() {
  const auto& q = model_.q();
  const auto& dq = model_.dq();
  const double limit = config_.limits.max_torque_nm;
  for (size_t i = 0; i < config_.model.joints; ++i) {
    const double tau = active_.stiffness[i] * (active_.q_des_rad[i] - q[i]) +
                       active_.damping[i] * (active_.dq_des_radps[i] - dq[i]) + active_.tau_ff_nm[i];
    // torque saturation per joint, always
    tau_nm_[i] = std::clamp(tau, -limit, limit);
    if (tau_nm_[i] != tau) ++torque_saturations_;
  }
}

void FollowerNode::publish_state() {
  const size_t n = config_.model.joints;
  auto& st = state_pub_.sample();
  transport::copy_joints(model_.q(), n, st.q_rad());
  transport::copy_joints(model_.dq(), n, st.dq_radps());
  transport::copy_joints(tau_nm_, n, st.tau_measured_nm());
  transport::copy_joints(model_.contact_torque(), n, st.tau_ext_nm());
  state_pub_.publish();

  // the contact torque on joint 0 seen as a force at the tool, normal to the lever
  auto& w = wrench_pub_.sample();
  w.force_n().x(model_.contact_torque()[0] / config_.wrench_lever_m);
  w.force_n().y(0.0);
  w.force_n().z(0.0);
  w.torque_nm().z(model_.contact_torque()[0]);
  wrench_pub_.publish();
}

void FollowerNode::cycle(const CycleTick& tick) {
  take_command(tick.now_ns);
  run_watchdog(tick.now_ns);
  compute_torque();
  model_.step(tau_nm_, period_s_);
  publish_state();
}

void FollowerNode::active_faults(std::vector<uint32_t>& faults) const {
  if (state_ == msg::STATE_SAFE_HOLD) faults.push_back(msg::FAULT_STALE_INPUT);
  if (validator_.rejected() > 0) faults.push_back(msg::FAULT_COMMAND_REJECTED);
}

void FollowerNode::fill_report(runtime::NodeReport& report) const {
  report.add(command_);
  report.add(state_pub_);
  report.add(wrench_pub_);
  report.counters.emplace_back("watchdog_trips", static_cast<double>(watchdog_trips_));
  report.counters.emplace_back("torque_saturations", static_cast<double>(torque_saturations_));
  for (size_t i = 0; i < static_cast<size_t>(CommandIssue::kCount); ++i) {
    const auto issue = static_cast<CommandIssue>(i);
    report.counters.emplace_back(to_string(issue), static_cast<double>(validator_.count(issue)));
  }
}

}  // namespace teleop::follower
