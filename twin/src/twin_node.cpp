#include "twin_node.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "teleop/runtime/shutdown_signal.h"
#include "teleop/transport/joint_fields.h"
#include "joint_command_law.h"
#include "twin_joint_state.h"

namespace teleop::twin {
namespace {

const transport::TopicSpec<msg::JointState>& coupled_topic(const TwinConfig& c) {
  const bool follower = c.mode == TwinMode::kHil || c.coupled_to == TwinConfig::CoupledTo::kFollower;
  return follower ? transport::topics::kFollowerState : transport::topics::kLeaderState;
}

const transport::TopicSpec<msg::JointCommand>& command_topic(const HilConfig& c) {
  return c.command_topic == HilConfig::CommandTopic::kLeader ? transport::topics::kLeaderCommand
                                                             : transport::topics::kTwinCommand;
}

}  // namespace

TwinNode::TwinNode(const TwinConfig& config, runtime::NodeContext& context)
    : config_(config),
      sim_([&] {
        TwinModelConfig model = config.model;
        // lock-step: one model timestep per exchange, whatever the loop's rate cap
        model.period_s = config.mode == TwinMode::kLockstep ? 0.0 : 1.0 / context.node.rate_hz;
        return model;
      }()),
      joints_(sim_.joints()),
      state_pub_(context.participant, transport::topics::kTwinState, context.node.name),
      feedback_(context.participant, transport::topics::kTwinFeedback, context.node.name,
                config.coupled_to == TwinConfig::CoupledTo::kLeader ? "leader_device" : "follower", "single", joints_,
                {config.feedback_gain, config.feedback_cutoff_hz, context.node.rate_hz}),
      observations_(sim_, context.participant, context.node.name),
      stall_watch_(static_cast<int64_t>(config.peer_timeout_s * 1e9)) {
  if (config.joints != joints_) {
    throw ConfigError("twin.joints is " + std::to_string(config.joints) + " but " + config.model.model_path +
                      " drives " + std::to_string(joints_) + " joints");
  }
  if (config.mode == TwinMode::kLockstep) {
    // the exchange runs as fast as the controller answers; the loop rate only caps it
    lockstep_.emplace(context.participant, context.node.name, joints_, config.lockstep.timeout_s,
                      1.0 / context.node.rate_hz);
    if (config.lockstep.steps > 0 && !config.lockstep.trajectory_file.empty()) {
      trajectory_.reserve(config.lockstep.steps * 2 * joints_);
    }
  } else if (config.mode == TwinMode::kHil) {
    measured_.emplace(context.participant, coupled_topic(config));
  } else {
    coupled_.emplace(context.participant, coupled_topic(config), joints_, config.peer_timeout_s, sim_.q_rad(),
                     config.rejoin_speed_radps, 1.0 / context.node.rate_hz);
  }
  if (config.mode == TwinMode::kHil) {
    if (config.hil.goal_joints != joints_) {
      throw ConfigError("twin.hil.goal_rad: " + std::to_string(config.hil.goal_joints) + " angles, but the model drives " +
                        std::to_string(joints_) + " joints");
    }
    hil_.emplace(config.hil, joints_);
    hil_command_pub_.emplace(context.participant, command_topic(config.hil), context.node.name);
    hil_command_pub_->sample().robot("follower");
    hil_command_pub_->sample().arm("single");
    hil_->presize(hil_command_pub_->sample());
  }
  if (config.mmt.enabled) {
    // model-mediated: the follower tracks this twin's arm as joint impedance commands
    mmt_command_.emplace(context.participant, transport::topics::kTwinCommand, context.node.name, "single", joints_,
                         config.mmt.stiffness_nm_per_rad, config.mmt.damping_nms_per_rad);
    if (config.mmt.correction) correction_.emplace(*config.mmt.correction, sim_, context.participant);
  }
  auto& st = state_pub_.sample();
  st.robot("twin");
  st.arm("single");
  transport::presize_joint_state(st, joints_);
}

void TwinNode::cycle(const CycleTick& tick) {
  observations_.mark_cycle(tick.now_ns);
  switch (config_.mode) {
    case TwinMode::kRealtime:
      cycle_coupled(tick);
      break;
    case TwinMode::kLockstep:
      cycle_lockstep();
      break;
    case TwinMode::kHil:
      cycle_hil(tick);
      break;
  }
  publish_state();
  observations_.publish(sim_);
}

void TwinNode::cycle_coupled(const CycleTick& tick) {
  const bool fresh = coupled_->update(tick.now_ns, state_, stall_watch_.stalled(tick));
  // the follower's measurements move the twin's environment between steps
  if (correction_) correction_->cycle(sim_, sim_.config().period_s);
  // without a coupled robot the twin holds the last pose it was given
  sim_.step_coupled(coupled_->q_rad());
  feedback_.render(sim_.constraint_torque_nm(), fresh);
  // a twin without its leader commands nothing: the follower's watchdog holds it
  if (mmt_command_ && fresh) mmt_command_->publish(sim_.q_rad(), sim_.dq_radps(), feedback_.contact_torque_nm());
}

void TwinNode::cycle_lockstep() {
  if (state_ == msg::STATE_STARTING && !lockstep_->connected()) return;
  write_joint_state(sim_, 0, joints_, lockstep_->state());
  const LockstepLink::Result result = lockstep_->exchange();
  if (result == LockstepLink::Result::kPending) return;
  if (result == LockstepLink::Result::kStalled) {
    if (state_ != msg::STATE_SAFE_HOLD) ++stalls_;
    state_ = msg::STATE_SAFE_HOLD;
    return;
  }
  state_ = msg::STATE_RUNNING;
  if (command_usable(lockstep_->command(), joints_)) {
    command_torque(lockstep_->command(), sim_.q_rad(), joints_, tau_cmd_, damping_cmd_);
  } else {
    ++rejected_samples_;
    tau_cmd_.fill(0.0);
    damping_cmd_.fill(0.0);
  }
  sim_.step_torque(tau_cmd_, damping_cmd_);
  feedback_.render(sim_.constraint_torque_nm(), true);
  record_trajectory();
  if (config_.lockstep.steps > 0 && lockstep_->steps() >= config_.lockstep.steps) runtime::request_shutdown();
}

void TwinNode::cycle_hil(const CycleTick& tick) {
  const int received = measured_->poll();
  const bool fresh = measured_->age_ns(tick.now_ns) < static_cast<int64_t>(config_.hil.peer_timeout_s * 1e9);
  if (received > 0) {
    const auto& measured = measured_->latest();
    if (transport::read_joints(measured.q_rad(), joints_, q_coupled_) &&
        transport::read_joints(measured.dq_radps(), joints_, dq_coupled_)) {
      // the real robot's state supersedes the twin's
      sim_.set_state(q_coupled_, dq_coupled_);
    } else {
      ++rejected_samples_;
    }
  }
  if (!fresh || !measured_->has_sample()) {
    // no measured robot: no command (its own watchdog holds it)
    if (state_ == msg::STATE_RUNNING) state_ = msg::STATE_SAFE_HOLD;
    return;
  }
  if (state_ == msg::STATE_STARTING) hil_start_s_ = static_cast<double>(tick.now_ns) * 1e-9;
  state_ = msg::STATE_RUNNING;
  hil_->compute(sim_.q_rad(), static_cast<double>(tick.now_ns) * 1e-9 - hil_start_s_, hil_command_pub_->sample());
  hil_command_pub_->publish();
  goal_error_rad_ = hil_->goal_error_rad(sim_.q_rad());
}

void TwinNode::publish_state() {
  write_joint_state(sim_, 0, joints_, state_pub_.sample());
  state_pub_.publish();
}

void TwinNode::record_trajectory() {
  // capacity was reserved for the configured steps: push_back never allocates here
  if (trajectory_.capacity() < trajectory_.size() + 2 * joints_) return;
  for (size_t i = 0; i < joints_; ++i) trajectory_.push_back(sim_.q_rad()[i]);
  for (size_t i = 0; i < joints_; ++i) trajectory_.push_back(sim_.dq_radps()[i]);
}

void TwinNode::write_trajectory() const {
  const std::string& path = config_.lockstep.trajectory_file;
  if (path.empty()) return;
  FILE* out = std::fopen(path.c_str(), "w");
  if (out == nullptr) throw std::runtime_error("cannot write the trajectory file '" + path + "'");
  const size_t width = 2 * joints_;
  for (size_t k = 0; k < trajectory_.size(); ++k) {
    // hex floats: the exact bits, so two files are equal exactly when the runs are
    std::fprintf(out, "%a%c", trajectory_[k], (k + 1) % width == 0 ? '\n' : ' ');
  }
  std::fclose(out);
}

void TwinNode::active_faults(std::vector<uint32_t>& faults) const {
  if (state_ == msg::STATE_SAFE_HOLD) {
    faults.push_back(config_.mode == TwinMode::kRealtime ? msg::FAULT_PEER_LOST : msg::FAULT_STALE_INPUT);
  }
  if (rejected_samples() > 0) faults.push_back(msg::FAULT_COMMAND_REJECTED);
}

void TwinNode::fill_report(runtime::NodeReport& report) const {
  if (coupled_) report.add(coupled_->subscription());
  if (measured_) report.add(*measured_);
  report.add(state_pub_);
  report.add(feedback_.publication());
  // hardware in the loop integrates nothing: the robot is the simulation
  observations_.fill_report(report, sim_, config_.mode != TwinMode::kHil);
  report.counters.emplace_back("peak_feedback_nm", feedback_.peak_feedback_nm());
  report.counters.emplace_back("rejected_samples", static_cast<double>(rejected_samples()));
  if (lockstep_) {
    report.add(lockstep_->state_publication());
    report.add(lockstep_->command_subscription());
    report.counters.emplace_back("lockstep_steps", static_cast<double>(lockstep_->steps()));
    report.counters.emplace_back("lockstep_stalls", static_cast<double>(stalls_));
    report.counters.emplace_back("lockstep_first_step_resends", static_cast<double>(lockstep_->first_step_resends()));
    write_trajectory();
  } else if (coupled_) {
    report.counters.emplace_back("stall_holds", static_cast<double>(stall_watch_.stalls()));
  }
  if (hil_command_pub_) report.add(*hil_command_pub_);
  if (mmt_command_) report.add(mmt_command_->publication());
  if (hil_) report.counters.emplace_back("hil_goal_error_rad", goal_error_rad_);
  if (correction_) correction_->fill_report(report);
}

void TwinNode::trace_columns(std::vector<std::string>& columns) const {
  columns.emplace_back("state");
  for (size_t i = 0; i < joints_; ++i) columns.push_back("q_" + std::to_string(i));
  for (size_t i = 0; i < joints_; ++i) columns.push_back("tau_fb_" + std::to_string(i));
  if (correction_) correction_->trace_columns(columns);
}

void TwinNode::trace_row(double* row) const {
  *row++ = static_cast<double>(state_);
  row = std::copy_n(sim_.q_rad().begin(), joints_, row);
  row = std::copy_n(feedback_.feedback_nm().begin(), joints_, row);
  if (correction_) correction_->trace_row(row);
}

}  // namespace teleop::twin
