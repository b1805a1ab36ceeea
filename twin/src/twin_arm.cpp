#include "twin_arm.h"

#include <algorithm>
#include <cmath>

#include "teleop/transport/arm_topic.h"
#include "teleop/transport/joint_fields.h"
#include "twin_joint_state.h"

namespace teleop::twin {
namespace {

const transport::TopicSpec<msg::JointState>& coupled_topic(const TwinConfig& c) {
  return c.coupled_to == TwinConfig::CoupledTo::kFollower ? transport::topics::kFollowerState
                                                           : transport::topics::kLeaderState;
}

// the arm's part of the scene's start pose, from index 0
JointVector start_pose(const TwinSimulation& sim, size_t first, size_t joints) {
  JointVector q{};
  std::copy_n(sim.q_rad().begin() + static_cast<std::ptrdiff_t>(first), joints, q.begin());
  return q;
}

}  // namespace

TwinArm::TwinArm(const TwinConfig& config, TwinScene& scene, size_t first_joint, runtime::NodeContext& context)
    : config_(config),
      scene_(scene),
      first_(first_joint),
      joints_(config.joints),
      coupled_(context.participant, transport::arm_topic(coupled_topic(config), config.arm), joints_,
               config.peer_timeout_s, start_pose(scene_.simulation(), first_, joints_), config.rejoin_speed_radps,
               1.0 / context.node.rate_hz),
      state_pub_(context.participant, transport::arm_topic(transport::topics::kTwinState, config.arm), context.node.name),
      feedback_(context.participant, transport::arm_topic(transport::topics::kTwinFeedback, config.arm),
                context.node.name, config.coupled_to == TwinConfig::CoupledTo::kLeader ? "leader_device" : "follower",
                transport::arm_label(config.arm), joints_,
                {config.feedback_gain, config.feedback_cutoff_hz, context.node.rate_hz}) {
  if (config.mmt.enabled) {
    command_.emplace(context.participant, transport::arm_topic(transport::topics::kTwinCommand, config.arm),
                     context.node.name, transport::arm_label(config.arm), joints_, config.mmt.stiffness_nm_per_rad,
                     config.mmt.damping_nms_per_rad);
  }
  q_rad_ = start_pose(scene_.simulation(), first_, joints_);
  auto& st = state_pub_.sample();
  st.robot("twin");
  st.arm(transport::arm_label(config.arm));
  transport::presize_joint_state(st, joints_);
}

const JointVector& TwinArm::slice(const JointVector& all) {
  std::copy_n(all.begin() + static_cast<std::ptrdiff_t>(first_), joints_, slice_.begin());
  return slice_;
}

void TwinArm::cycle(const CycleTick& tick) {
  fresh_ = coupled_.update(tick.now_ns, state_);
  // without a fresh robot arm the twin arm holds the last target it was given
  std::copy_n(coupled_.q_rad().begin(), joints_, scene_.targets().begin() + static_cast<std::ptrdiff_t>(first_));
}

void TwinArm::publish_step() {
  const TwinSimulation& sim = scene_.simulation();
  q_rad_ = slice(sim.q_rad());
  dq_radps_ = slice(sim.dq_radps());
  coupling_error_rad_ = 0.0;
  for (size_t i = 0; i < joints_; ++i) {
    coupling_error_rad_ = std::max(coupling_error_rad_, std::abs(coupled_.q_rad()[i] - q_rad_[i]));
    if (fresh_) coupling_.add(coupled_.q_rad()[i] - q_rad_[i]);
  }
  feedback_.render(slice(sim.constraint_torque_nm()), fresh_);
  write_joint_state(sim, first_, joints_, state_pub_.sample());
  state_pub_.publish();
  // an arm without its robot arm commands nothing: the follower arm's watchdog holds it
  if (command_ && fresh_) command_->publish(q_rad_, dq_radps_, feedback_.contact_torque_nm());
}

void TwinArm::active_faults(std::vector<uint32_t>& faults) const {
  if (state_ == msg::STATE_SAFE_HOLD) faults.push_back(msg::FAULT_PEER_LOST);
  if (coupled_.rejected() > 0) faults.push_back(msg::FAULT_COMMAND_REJECTED);
}

void TwinArm::fill_report(runtime::NodeReport& report) const {
  report.add(coupled_.subscription());
  report.add(state_pub_);
  report.add(feedback_.publication());
  if (command_) report.add(command_->publication());
  report.counters.emplace_back("peak_feedback_nm", feedback_.peak_feedback_nm());
  report.counters.emplace_back("rejected_samples", static_cast<double>(coupled_.rejected()));
  report.counters.emplace_back("coupling_rmse_rad", coupling_.rms());
  report.counters.emplace_back("coupling_max_error_rad", coupling_.max_abs());
}

void TwinArm::trace_columns(std::vector<std::string>& columns) const {
  columns.emplace_back("state");
  for (size_t i = 0; i < joints_; ++i) columns.push_back("q_" + std::to_string(i));
  for (size_t i = 0; i < joints_; ++i) columns.push_back("tau_fb_" + std::to_string(i));
  columns.emplace_back("coupling_error_rad");
}

void TwinArm::trace_row(double* row) const {
  *row++ = static_cast<double>(state_);
  row = std::copy_n(q_rad_.begin(), joints_, row);
  row = std::copy_n(feedback_.feedback_nm().begin(), joints_, row);
  *row = coupling_error_rad_;
}

}  // namespace teleop::twin
