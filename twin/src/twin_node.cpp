#include "teleop/twin/twin_node.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "teleop/runtime/shutdown_signal.h"
#include "teleop/transport/joint_fields.h"
#include "teleop/twin/joint_command_law.h"

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

double norm3(const std::array<double, 3>& v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

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
      feedback_filter_(config.feedback_cutoff_hz, context.node.rate_hz),
      state_pub_(context.participant, transport::topics::kTwinState, context.node.name),
      feedback_pub_(context.participant, transport::topics::kTwinFeedback, context.node.name),
      distances_pub_(context.participant, transport::topics::kTwinDistances, context.node.name) {
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
  } else {
    coupled_.emplace(context.participant, coupled_topic(config));
  }
  if (config.mode == TwinMode::kHil) {
    if (config.hil.goal_joints != joints_) {
      throw ConfigError("twin.hil.goal_rad: " + std::to_string(config.hil.goal_joints) + " angles, but the model drives " +
                        std::to_string(joints_) + " joints");
    }
    hil_.emplace(config.hil, joints_);
    command_pub_.emplace(context.participant, command_topic(config.hil), context.node.name);
    command_pub_->sample().robot("follower");
    command_pub_->sample().arm("single");
    hil_->presize(command_pub_->sample());
  }
  if (config.mmt.enabled) {
    // model-mediated: the follower tracks this twin's arm as joint impedance commands
    command_pub_.emplace(context.participant, transport::topics::kTwinCommand, context.node.name);
    auto& cmd = command_pub_->sample();
    cmd.robot("follower");
    cmd.arm("single");
    cmd.mode().assign(joints_, msg::CONTROL_JOINT_IMPEDANCE);
    transport::presize(joints_, cmd.q_des_rad(), cmd.dq_des_radps(), cmd.tau_ff_nm());
    cmd.stiffness_nm_per_rad().assign(joints_, config.mmt.stiffness_nm_per_rad);
    cmd.damping_nms_per_rad().assign(joints_, config.mmt.damping_nms_per_rad);
    if (config.mmt.correction) correction_.emplace(*config.mmt.correction, sim_, context.participant);
  }
  auto& st = state_pub_.sample();
  st.robot("twin");
  st.arm("single");
  transport::presize_joint_state(st, joints_);
  feedback_pub_.sample().robot(config.coupled_to == TwinConfig::CoupledTo::kLeader ? "leader_device" : "follower");
  feedback_pub_.sample().arm("single");
  transport::presize(joints_, feedback_pub_.sample().tau_nm());
  const PairObserver& distances = sim_.distance_pairs();
  for (size_t i = 0; i < distances.size(); ++i) distances_pub_.sample().pair().push_back(distances.name(i));
  transport::presize(distances.size(), distances_pub_.sample().distance_m());
  const PairObserver& contacts = sim_.contact_pairs();
  for (size_t i = 0; i < contacts.size(); ++i) {
    // the topic keeps its name; the spec only borrows it for the writer's creation
    const std::string topic = transport::topics::kTwinContactWrenchPrefix + contacts.name(i);
    wrench_pubs_.push_back(std::make_unique<transport::Publication<msg::WrenchStamped>>(
        context.participant, transport::TopicSpec<msg::WrenchStamped>{topic.c_str(), transport::QosPreset::kStream},
        context.node.name));
    wrench_pubs_.back()->sample().frame("world");
  }
  q_coupled_ = sim_.q_rad();
  min_distance_m_ = sim_.config().distance_range_m;
  sim_start_s_ = sim_.time_s();
}

void TwinNode::cycle(const CycleTick& tick) {
  if (first_cycle_ns_ < 0) first_cycle_ns_ = tick.now_ns;
  last_cycle_ns_ = tick.now_ns;
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
  publish_observations();
}

void TwinNode::cycle_coupled(const CycleTick& tick) {
  if (coupled_->poll() > 0 && !transport::read_joints(coupled_->latest().q_rad(), joints_, q_coupled_)) {
    ++rejected_samples_;
  }
  const bool fresh = coupled_->age_ns(tick.now_ns) < static_cast<int64_t>(config_.peer_timeout_s * 1e9);
  if (fresh) {
    state_ = msg::STATE_RUNNING;
  } else if (state_ == msg::STATE_RUNNING) {
    state_ = msg::STATE_SAFE_HOLD;
  }
  // the follower's measurements move the twin's environment between steps
  if (correction_) correction_->cycle(sim_, sim_.config().period_s);
  // without a coupled robot the twin holds the last pose it was given
  sim_.step_coupled(q_coupled_);
  render_feedback(fresh);
  // a twin without its leader commands nothing: the follower's watchdog holds it
  if (command_pub_ && fresh) command_follower();
}

void TwinNode::command_follower() {
  auto& cmd = command_pub_->sample();
  transport::copy_joints(sim_.q_rad(), joints_, cmd.q_des_rad());
  transport::copy_joints(sim_.dq_radps(), joints_, cmd.dq_des_radps());
  // and the force: the follower pushes on its environment as hard as the twin's environment
  // pushes back on the twin (tracking the position alone, it would only touch the wall)
  for (size_t i = 0; i < joints_; ++i) cmd.tau_ff_nm()[i] = -contact_torque_nm_[i];
  command_pub_->publish();
}

void TwinNode::cycle_lockstep() {
  if (state_ == msg::STATE_STARTING && !lockstep_->connected()) return;
  auto& st = lockstep_->state();
  transport::copy_joints(sim_.q_rad(), joints_, st.q_rad());
  transport::copy_joints(sim_.dq_radps(), joints_, st.dq_radps());
  transport::copy_joints(sim_.tau_nm(), joints_, st.tau_measured_nm());
  transport::copy_joints(sim_.constraint_torque_nm(), joints_, st.tau_ext_nm());
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
  render_feedback(true);
  record_trajectory();
  if (config_.lockstep.steps > 0 && lockstep_->steps() >= config_.lockstep.steps) runtime::request_shutdown();
}

void TwinNode::cycle_hil(const CycleTick& tick) {
  const int received = coupled_->poll();
  const bool fresh = coupled_->age_ns(tick.now_ns) < static_cast<int64_t>(config_.hil.peer_timeout_s * 1e9);
  if (received > 0) {
    const auto& measured = coupled_->latest();
    if (transport::read_joints(measured.q_rad(), joints_, q_coupled_) &&
        transport::read_joints(measured.dq_radps(), joints_, dq_coupled_)) {
      // the real robot's state supersedes the twin's
      sim_.set_state(q_coupled_, dq_coupled_);
    } else {
      ++rejected_samples_;
    }
  }
  if (!fresh || !coupled_->has_sample()) {
    // no measured robot: no command (its own watchdog holds it)
    if (state_ == msg::STATE_RUNNING) state_ = msg::STATE_SAFE_HOLD;
    return;
  }
  if (state_ == msg::STATE_STARTING) hil_start_s_ = static_cast<double>(tick.now_ns) * 1e-9;
  state_ = msg::STATE_RUNNING;
  hil_->compute(sim_.q_rad(), static_cast<double>(tick.now_ns) * 1e-9 - hil_start_s_, command_pub_->sample());
  command_pub_->publish();
  goal_error_rad_ = hil_->goal_error_rad(sim_.q_rad());
}

void TwinNode::render_feedback(bool coupled_fresh) {
  const JointVector& filtered = feedback_filter_.apply(sim_.constraint_torque_nm(), joints_);
  contact_torque_nm_ = filtered;
  for (size_t i = 0; i < joints_; ++i) {
    // without a fresh coupled robot there is nothing to render on
    feedback_nm_[i] = coupled_fresh ? config_.feedback_gain * filtered[i] : 0.0;
    peak_feedback_nm_ = std::max(peak_feedback_nm_, std::abs(feedback_nm_[i]));
  }
  transport::copy_joints(feedback_nm_, joints_, feedback_pub_.sample().tau_nm());
  feedback_pub_.publish();
}

void TwinNode::publish_observations() {
  auto& st = state_pub_.sample();
  transport::copy_joints(sim_.q_rad(), joints_, st.q_rad());
  transport::copy_joints(sim_.dq_radps(), joints_, st.dq_radps());
  transport::copy_joints(sim_.tau_nm(), joints_, st.tau_measured_nm());
  transport::copy_joints(sim_.constraint_torque_nm(), joints_, st.tau_ext_nm());
  state_pub_.publish();

  auto& distances = distances_pub_.sample().distance_m();
  for (size_t i = 0; i < distances.size(); ++i) {
    distances[i] = sim_.distance_m(i);
    min_distance_m_ = std::min(min_distance_m_, distances[i]);
  }
  if (!distances.empty()) distances_pub_.publish();

  for (size_t i = 0; i < wrench_pubs_.size(); ++i) {
    const Wrench w = sim_.contact_wrench(i);
    peak_contact_force_n_ = std::max(peak_contact_force_n_, norm3(w.force_n));
    transport::set_wrench(wrench_pubs_[i]->sample(), w.force_n.data(), w.torque_nm.data());
    wrench_pubs_[i]->publish();
  }
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
  if (rejected_samples_ > 0) faults.push_back(msg::FAULT_COMMAND_REJECTED);
}

void TwinNode::fill_report(runtime::NodeReport& report) const {
  if (coupled_) report.add(*coupled_);
  report.add(state_pub_);
  report.add(feedback_pub_);
  report.add(distances_pub_);
  for (const auto& pub : wrench_pubs_) report.add(*pub);
  // hardware in the loop integrates nothing: the robot is the simulation
  const double sim_s = config_.mode == TwinMode::kHil ? 0.0 : sim_.time_s() - sim_start_s_;
  const double wall_s = first_cycle_ns_ < 0 ? 0.0 : static_cast<double>(last_cycle_ns_ - first_cycle_ns_) * 1e-9;
  report.counters.emplace_back("sim_time_s", sim_s);
  report.counters.emplace_back("rt_factor", wall_s > 0 ? sim_s / wall_s : 0.0);
  report.counters.emplace_back("peak_feedback_nm", peak_feedback_nm_);
  report.counters.emplace_back("peak_contact_force_n", peak_contact_force_n_);
  report.counters.emplace_back("min_distance_m", min_distance_m_);
  report.counters.emplace_back("rejected_samples", static_cast<double>(rejected_samples_));
  report.counters.emplace_back("mujoco_warnings", static_cast<double>(sim_.warnings()));
  if (lockstep_) {
    report.add(lockstep_->state_publication());
    report.add(lockstep_->command_subscription());
    report.counters.emplace_back("lockstep_steps", static_cast<double>(lockstep_->steps()));
    report.counters.emplace_back("lockstep_stalls", static_cast<double>(stalls_));
    write_trajectory();
  }
  if (command_pub_) report.add(*command_pub_);
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
  row = std::copy_n(feedback_nm_.begin(), joints_, row);
  if (correction_) correction_->trace_row(row);
}

}  // namespace teleop::twin
