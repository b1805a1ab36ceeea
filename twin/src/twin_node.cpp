#include "teleop/twin/twin_node.h"

#include <cmath>

#include "teleop/common/joint_config.h"
#include "teleop/transport/joint_fields.h"

namespace teleop::twin {

TwinConfig TwinNode::parse_config(const ConfigNode& root) {
  const ConfigNode s = root.child("twin");
  TwinConfig c;
  const size_t n = read_joint_count(s);
  c.model = read_joint_model(s.child("model"), n);
  c.home_rad = read_joint_list(s, "home_rad", n, Range{-2 * M_PI, 2 * M_PI}, 0.0);
  c.coupling_stiffness_nm_per_rad = s.get_double("coupling_stiffness_nm_per_rad", Range{0, 1e5}, c.coupling_stiffness_nm_per_rad);
  c.coupling_damping_nms_per_rad = s.get_double("coupling_damping_nms_per_rad", Range{0, 1e4}, c.coupling_damping_nms_per_rad);
  c.feedback_gain = s.get_double("feedback_gain", Range{0, 10}, c.feedback_gain);
  c.feedback_cutoff_hz = s.get_double("feedback_cutoff_hz", Range{0, 1e4}, c.feedback_cutoff_hz);
  c.peer_timeout_s = s.get_double("peer_timeout_ms", Range{1, 60'000}, 100) * 1e-3;
  return c;
}

TwinNode::TwinNode(const TwinConfig& config, runtime::NodeContext& context)
    : config_(config),
      period_s_(1.0 / context.node.rate_hz),
      model_(config.model),
      feedback_filter_(config.feedback_cutoff_hz, context.node.rate_hz),
      leader_state_(context.participant, transport::topics::kLeaderState),
      state_pub_(context.participant, transport::topics::kTwinState, context.node.name),
      feedback_pub_(context.participant, transport::topics::kTwinFeedback, context.node.name) {
  model_.reset(config.home_rad);
  q_coupled_ = config.home_rad;
  const size_t n = config.model.joints;
  auto& st = state_pub_.sample();
  st.robot("twin");
  st.arm("single");
  transport::presize_joint_state(st, n);
  feedback_pub_.sample().robot("leader_device");
  feedback_pub_.sample().arm("single");
  transport::presize(n, feedback_pub_.sample().tau_nm());
}

void TwinNode::couple() {
  const auto& q = model_.q();
  const auto& dq = model_.dq();
  for (size_t i = 0; i < config_.model.joints; ++i) {
    tau_nm_[i] = config_.coupling_stiffness_nm_per_rad * (q_coupled_[i] - q[i]) - config_.coupling_damping_nms_per_rad * dq[i];
  }
}

void TwinNode::publish(bool render_feedback) {
  const size_t n = config_.model.joints;
  auto& st = state_pub_.sample();
  transport::copy_joints(model_.q(), n, st.q_rad());
  transport::copy_joints(model_.dq(), n, st.dq_radps());
  transport::copy_joints(tau_nm_, n, st.tau_measured_nm());
  transport::copy_joints(model_.contact_torque(), n, st.tau_ext_nm());
  state_pub_.publish();

  const JointVector& filtered = feedback_filter_.apply(model_.contact_torque(), n);
  for (size_t i = 0; i < n; ++i) {
    // without a fresh coupled robot there is nothing to render on
    feedback_nm_[i] = render_feedback ? config_.feedback_gain * filtered[i] : 0.0;
    peak_feedback_nm_ = std::max(peak_feedback_nm_, std::abs(feedback_nm_[i]));
  }
  transport::copy_joints(feedback_nm_, n, feedback_pub_.sample().tau_nm());
  feedback_pub_.publish();
}

void TwinNode::cycle(const CycleTick& tick) {
  if (leader_state_.poll() > 0 && !transport::read_joints(leader_state_.latest().q_rad(), config_.model.joints, q_coupled_)) {
    ++rejected_samples_;
  }
  const bool fresh = leader_state_.age_ns(tick.now_ns) < static_cast<int64_t>(config_.peer_timeout_s * 1e9);
  if (fresh) {
    state_ = msg::STATE_RUNNING;
  } else if (state_ == msg::STATE_RUNNING) {
    state_ = msg::STATE_SAFE_HOLD;
  }
  couple();
  model_.step(tau_nm_, period_s_);
  publish(fresh);
}

void TwinNode::active_faults(std::vector<uint32_t>& faults) const {
  if (state_ == msg::STATE_SAFE_HOLD) faults.push_back(msg::FAULT_PEER_LOST);
  if (rejected_samples_ > 0) faults.push_back(msg::FAULT_COMMAND_REJECTED);
}

void TwinNode::fill_report(runtime::NodeReport& report) const {
  report.add(leader_state_);
  report.add(state_pub_);
  report.add(feedback_pub_);
  report.counters.emplace_back("peak_feedback_nm", peak_feedback_nm_);
  report.counters.emplace_back("rejected_samples", static_cast<double>(rejected_samples_));
}

}  // namespace teleop::twin
