#include "teleop/follower/follower_node.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <spdlog/spdlog.h>

#include "architectures/follower_architectures.h"
#include "limits_in_force.h"
#include "teleop/common/clock.h"
#include "teleop/transport/arm_topic.h"
#include "teleop/transport/joint_fields.h"

namespace teleop::follower {
namespace {

// the robot's own limits, tightened by the configured ones
JointLimits effective_limits(const FollowerConfig& config, const robot::RobotHardware& hardware) {
  return limits_in_force(config.limits, hardware.limits(), config.joints, hardware.name());
}

// a command stream follows one sender; another may take over once that one has been silent for a
// watchdog period (a restarted leader at once, a stray writer never while the leader streams)
StreamSessionPolicy command_sessions(const FollowerConfig& config) {
  StreamSessionPolicy policy;
  policy.takeover_silence_ns = static_cast<int64_t>(config.command_timeout_s * 1e9);
  return policy;
}

const transport::TopicSpec<msg::JointCommand>& joint_topic(const FollowerConfig& config) {
  return config.command_source == FollowerConfig::CommandSource::kTwin ? transport::topics::kTwinCommand
                                                                       : transport::topics::kLeaderCommand;
}

}  // namespace

FollowerNode::FollowerNode(const FollowerConfig& config, runtime::NodeContext& context)
    : FollowerNode(config, config.hardware->make(1.0 / context.node.rate_hz), context) {}

FollowerNode::FollowerNode(const FollowerConfig& config, std::unique_ptr<robot::RobotHardware> hardware,
                           runtime::NodeContext& context)
    : config_(config),
      hardware_(std::move(hardware)),
      control_(config.control, 1.0 / context.node.rate_hz),
      validator_(config.joints, effective_limits(config, *hardware_)),
      limiter_(config.joints, validator_.limits().max_torque_nm, config.max_torque_rate_nm_per_s, 1.0 / context.node.rate_hz),
      joint_commands_(context.participant, transport::arm_topic(joint_topic(config), config.arm), command_sessions(config)),
      cartesian_commands_(context.participant, transport::arm_topic(transport::topics::kLeaderCartesian, config.arm),
                          command_sessions(config)),
      reset_requests_(context.participant.make_reader(transport::topics::kResetRequest)),
      name_(context.node.name),
      state_pub_(context.participant, transport::arm_topic(transport::topics::kFollowerState, config.arm),
                 context.node.name),
      wrench_pub_(context.participant, transport::arm_topic(transport::topics::kFollowerWrench, config.arm),
                  context.node.name),
      reflex_(config.reflex),
      brake_(config.reflex.brake_share_per_cycle, 1.0 / context.node.rate_hz),
      rejoin_(config.joints, config.rejoin_speed_radps, 1.0 / context.node.rate_hz),
      stall_watch_(static_cast<int64_t>(config.command_timeout_s * 1e9)) {
  if (hardware_->joints() != config.joints) {
    throw std::runtime_error("follower.joints is " + std::to_string(config.joints) + " but the robot (" +
                             hardware_->name() + ") has " + std::to_string(hardware_->joints()) + " joints");
  }
  spdlog::info("{}: joint limits {}", context.node.name, limits_text(validator_.limits(), config.limits, config.joints));
  if (!config.calibration_file.empty()) {
    const control::ArmCalibration& c = config.control.calibration;
    spdlog::info("{}: calibration {}: payload {:.4f} kg at [{:.4f}, {:.4f}, {:.4f}] m held and taken out of the external "
                 "torque, with a bias of up to {:.3f} Nm",
                 context.node.name, config.calibration_file, c.payload.mass_kg, c.payload.com_m.x(), c.payload.com_m.y(),
                 c.payload.com_m.z(), c.torque_bias_nm.cwiseAbs().maxCoeff());
  }
  auto& st = state_pub_.sample();
  st.robot(hardware_->name());
  st.arm(transport::arm_label(config.arm));
  transport::presize_joint_state(st, config.joints);
  wrench_pub_.sample().frame("base");
  // a state gone stale since the robot connected still says where it is: the first cycles hold it
  if (hardware_->read(arm_) == robot::HardwareStatus::kFault) throw std::runtime_error("the robot hardware cannot be read");
  // until a command arrives, hold the pose the robot is in, from the torque it holds it with
  hold_current_pose(active_, config_.hold_stiffness_nm_per_rad, config_.hold_damping_nms_per_rad);
  limiter_.reset(arm_.tau_measured_nm);
  const double h = 1.0 / context.node.rate_hz;
  architecture_ = make_follower_architecture({context.participant, context.node.name, config.arm, h,
                                              config.teleoperation ? &*config.teleoperation : nullptr});
  // the commander uses one of the two streams: the other is not waited for
  if (architecture_->cartesian()) {
    joint_commands_.mark_optional();
  } else {
    cartesian_commands_.mark_optional();
  }
  joint_commands_.accept_only(config.accept_commands_from);
  cartesian_commands_.accept_only(config.accept_commands_from);
}

FollowerNode::~FollowerNode() = default;

void FollowerNode::hold_current_pose(ValidCommand& hold, double stiffness, double damping) {
  hold = ValidCommand{};
  hold.mode = msg::CONTROL_JOINT_IMPEDANCE;
  std::copy_n(arm_.q_rad.begin(), config_.joints, hold.q_des_rad.begin());
  std::fill_n(hold.stiffness.begin(), config_.joints, stiffness);
  std::fill_n(hold.damping.begin(), config_.joints, damping);
  // commands that resume later travel from here
  held_q_rad_ = hold.q_des_rad;
  rejoin_.stop();
}

void FollowerNode::take_commands(int64_t now_ns) {
  const int64_t now_system_ns = system_now_ns();
  // a command replaces the active one only when valid; joint and Cartesian commands may both
  // arrive (a mode change), the Cartesian one is taken last
  take(joint_commands_, Source::kJoint, joint_session_, now_system_ns, now_ns);
  take(cartesian_commands_, Source::kCartesian, cartesian_session_, now_system_ns, now_ns);
}

template <typename Command>
void FollowerNode::take(transport::Subscription<Command>& commands, Source source, uint64_t& last_session,
                        int64_t now_system_ns, int64_t now_ns) {
  if (commands.poll() == 0) return;
  const uint64_t session = commands.session().session();
  // a command's age beyond its writer's fastest sample: no assumption that the two hosts' clocks agree
  const int64_t now_on_writers_clock_ns = now_system_ns - commands.clock_offset_ns();
  if (validator_.validate(commands.latest(), now_on_writers_clock_ns, active_, session) == CommandVerdict::kRejected) {
    // the sender learns it from the status (FlowStatus.in_force), the log from the first of each kind
    const CommandIssue why = validator_.last_rejection();
    commands.reject_latest(static_cast<uint32_t>(why), to_string(why));
    return;
  }
  source_ = source;
  liveliness_lost_at_command_ = commands.reader().liveliness_lost();
  last_valid_command_ns_ = now_ns;
  command_seq_ = commands.latest().header().seq();
  if (session == last_session) return;
  last_session = session;
  // a new sender (a restarted leader) is joined from where the robot holds; a latched reflex
  // stays latched: only an explicit reset clears it, never a new session
  ++command_sessions_;
}

void FollowerNode::emergency_stop(bool engaged) {
  emergency_stopped_ = engaged;
  // an enable resumes as after a hold: the watchdog joins fresh commands from the held pose
  if (!engaged || state_ == msg::STATE_FAULT) return;
  state_ = msg::STATE_SAFE_HOLD;
  hold_cause_ = msg::FAULT_EMERGENCY_STOP;
  coming_to_rest_ = true;
  architecture_->restart();
}

bool FollowerNode::enable_requested() {
  if (!awaiting_enable_) return false;
  // the watchdog joins the commands from the held pose as soon as they flow
  awaiting_enable_ = false;
  return true;
}

void FollowerNode::bring_to_rest() {
  constexpr double kAtRestRadps = 0.02;
  hold_current_pose(active_, config_.hold_stiffness_nm_per_rad, config_.hold_damping_nms_per_rad);
  double fastest = 0.0;
  for (size_t i = 0; i < config_.joints; ++i) fastest = std::max(fastest, std::abs(arm_.dq_radps[i]));
  if (fastest < kAtRestRadps) coming_to_rest_ = false;
}

void FollowerNode::take_reset_requests() {
  while (reset_requests_.take_next(reset_request_)) {
    if (reset_request_.target() != name_) continue;
    ++resets_;
    reflex_.reset();
  }
}

bool FollowerNode::source_lost(double silence_s) const {
  const auto lapsed = [&](const auto& subscription) {
    const auto& reader = subscription.reader();
    if (reader.alive_writers() != 0) return false;
    // a writer whose liveliness lapsed since its last command: dead or cut off, do not wait for the timeout
    if (reader.liveliness_lost() > liveliness_lost_at_command_) return true;
    // Fast DDS renews automatic liveliness only with the writer participant's liveliness messages, not with its data: a
    // lapse reported while commands still came (a starved leader) leaves the writer "not alive" until the next such
    // message. Silent for a whole lease on top of that, it is as gone as one whose lapse came after its last command.
    return silence_s * 1e9 > static_cast<double>(reader.liveliness_lease_ns());
  };
  switch (source_) {
    case Source::kJoint: return lapsed(joint_commands_);
    case Source::kCartesian: return lapsed(cartesian_commands_);
    case Source::kNone: break;
  }
  return false;
}

void FollowerNode::run_watchdog(int64_t now_ns, bool stalled, bool robot_current) {
  // a hardware fault is not cleared by commands arriving, nor an emergency stop: both need an operator
  if (state_ == msg::STATE_FAULT || emergency_stopped_) return;
  const double silence_s = static_cast<double>(now_ns - last_valid_command_ns_) * 1e-9;
  const bool lost = source_lost(silence_s);
  // our own loop missed more than the timeout: what was drained now is a backlog, and the newest
  // command of it must not act as a step; hold for this cycle and rejoin from the held pose
  if (robot_current && !stalled && source_ != Source::kNone && silence_s < config_.command_timeout_s && !lost) {
    // a latched reflex holds until reset, a hold that waits for an enable until one comes, however
    // well the commands flow
    if (reflex_.latched() || awaiting_enable_) return;
    // commands (re)start after a hold: the robot joins them from the pose it held
    if (state_ != msg::STATE_RUNNING) rejoin_.start(held_q_rad_);
    state_ = msg::STATE_RUNNING;
    return;
  }
  if (state_ == msg::STATE_RUNNING) {
    // commands stopped: hold the pose we are at, in joint impedance, until they come back
    state_ = msg::STATE_SAFE_HOLD;
    if (!robot_current) {
      // the robot's measured state is the input that went stale: it holds by its own means
      hold_cause_ = msg::FAULT_STALE_INPUT;
      ++robot_state_holds_;
    } else {
      hold_cause_ = stalled ? msg::FAULT_LOOP_OVERRUN : lost ? msg::FAULT_PEER_LOST : msg::FAULT_STALE_INPUT;
      ++(stalled ? stall_holds_ : watchdog_trips_);
      if (lost) ++liveliness_trips_;
      if (!stalled) watchdog_latency_max_s_ = std::max(watchdog_latency_max_s_, silence_s);
    }
    hold_current_pose(active_, config_.hold_stiffness_nm_per_rad, config_.hold_damping_nms_per_rad);
    if (config_.enable_after_hold) {
      awaiting_enable_ = true;
      ++holds_awaiting_enable_;
    }
    // the channel's session ended with the command source: both ends start their bookkeeping afresh
    architecture_->restart();
  }
}

void FollowerNode::run_reflex() {
  if (state_ == msg::STATE_FAULT) return;
  const auto dq = Eigen::Map<const control::JointVector>(arm_.dq_radps.data());
  if (!reflex_.check(control_.external_torque(), control_.wrench(), dq)) return;
  // tripped: stop moving into the contact, yield to it, and tell the operator
  state_ = msg::STATE_SAFE_HOLD;
  const SafetyReflexConfig& r = reflex_.config();
  // a contact is yielded to; a joint too fast is also braked to a stop (command_torque)
  hold_current_pose(reflex_hold_, r.hold_stiffness_nm_per_rad, r.hold_damping_nms_per_rad);
  architecture_->restart();
}

void FollowerNode::apply_passivity() {
  // a latched reflex holds compliantly whatever comes in; otherwise the command, joined smoothly
  controlled_ = reflex_.latched() ? &reflex_hold_ : &rejoin_.apply(active_);
  // the architecture's correction (pfc_tdpa's passivity controller) of the command as received
  if (const ValidCommand* corrected = architecture_->correct(active_, state_ == msg::STATE_RUNNING, control_.wrench())) {
    controlled_ = corrected;
  }
}

void FollowerNode::command_torque(const ValidCommand& command) {
  control::JointVector tau = control_.compute(arm_, command);
  if (reflex_.latched() && reflex_.last_cause() == ReflexCause::kJointVelocity) {
    const auto dq = Eigen::Map<const control::JointVector>(arm_.dq_radps.data());
    brake_.apply(control_.mass(), dq, validator_.limits().max_torque_nm, tau);
  }
  const bool subtract_gravity = hardware_->compensates_gravity();
  for (size_t i = 0; i < config_.joints; ++i) total_nm_[i] = tau[static_cast<Eigen::Index>(i)];
  // saturation and rate limit act on what the drives produce: the total torque; a latched
  // reflex brakes or yields at once, unlimited in rate
  limiter_.apply(total_nm_, !reflex_.latched());
  torque_ratio_ = 0.0;
  for (size_t i = 0; i < config_.joints; ++i) {
    torque_ratio_ = std::max(torque_ratio_, std::abs(total_nm_[i]) / validator_.limits().max_torque_nm[i]);
  }
  for (size_t i = 0; i < config_.joints; ++i) {
    command_nm_[i] = total_nm_[i] - (subtract_gravity ? control_.gravity()[static_cast<Eigen::Index>(i)] : 0.0);
  }
}

void FollowerNode::record_metrics() {
  if (control_.mode() != last_mode_) {
    ++mode_changes_;
    last_mode_ = control_.mode();
  }
  const auto& r = control_.observer_torque();
  const auto& d = control_.direct_torque();
  for (size_t i = 0; i < config_.joints; ++i) {
    const auto k = static_cast<Eigen::Index>(i);
    observer_vs_hardware_.add(r[k] - arm_.tau_ext_nm[i]);
    direct_vs_hardware_.add(d[k] - arm_.tau_ext_nm[i]);
  }
  if (state_ != msg::STATE_RUNNING || control_.blending() || rejoin_.active()) return;
  if (active_.mode == msg::CONTROL_CARTESIAN_IMPEDANCE) {
    const Eigen::Vector3d target(active_.x_des_m.data());
    cartesian_tracking_.add((target - control_.ee_position()).norm());
  } else if (active_.mode != msg::CONTROL_GRAVITY) {
    for (size_t i = 0; i < config_.joints; ++i) joint_tracking_.add(active_.q_des_rad[i] - arm_.q_rad[i]);
  }
}

void FollowerNode::publish_state() {
  const size_t n = config_.joints;
  const control::JointVector& ext = control_.external_torque();
  auto& st = state_pub_.sample();
  transport::copy_joints(arm_.q_rad, n, st.q_rad());
  transport::copy_joints(arm_.dq_radps, n, st.dq_radps());
  transport::copy_joints(arm_.tau_measured_nm, n, st.tau_measured_nm());
  std::copy_n(ext.data(), n, st.tau_ext_nm().begin());
  state_pub_.publish();

  const control::Vector6& w = control_.wrench();
  peak_external_force_n_ = std::max(peak_external_force_n_, w.head<3>().norm());
  peak_external_moment_nm_ = std::max(peak_external_moment_nm_, w.tail<3>().norm());
  peak_external_joint_torque_nm_ = std::max(peak_external_joint_torque_nm_, ext.head(static_cast<Eigen::Index>(n)).cwiseAbs().maxCoeff());
  transport::set_wrench(wrench_pub_.sample(), w.data(), w.data() + 3);
  wrench_pub_.publish();
}

bool FollowerNode::command_robot() {
  run_reflex();
  apply_passivity();
  command_torque(*controlled_);
  // a robot commanded in positions tracks the joint reference; a Cartesian or gravity command has
  // none in joint space, so such a robot is told to stay where it is
  const ValidCommand& c = *controlled_;
  const bool joint_space = c.mode == msg::CONTROL_JOINT_IMPEDANCE;
  hardware_->set_reference(joint_space ? c.q_des_rad : arm_.q_rad, joint_space ? c.dq_des_radps : JointVector{});
  return hardware_->write(command_nm_) == robot::HardwareStatus::kOk;
}

void FollowerNode::cycle(const CycleTick& tick) {
  // read, compute, write: the torque acts on the state it was computed from, also on a scene
  // shared by several arms, which moves on only once every arm wrote (follower_arms.cpp)
  const robot::HardwareStatus read = hardware_->read(arm_);
  // nothing is computed from a stale state: the robot holds by its own means until it is current
  const bool robot_current = read != robot::HardwareStatus::kStale;
  if (robot_current) control_.estimate(arm_);
  // the watchdog counts control cycles (their deadlines): a cycle released late neither
  // shortens nor stretches the timeout
  const bool stalled = stall_watch_.stalled(tick);
  // stopped, or holding until an enable (after_hold: enable), no command is taken: the newest
  // waits in its reader for the enable
  if (!emergency_stopped_ && !awaiting_enable_) take_commands(tick.deadline_ns);
  take_reset_requests();
  run_watchdog(tick.deadline_ns, stalled, robot_current);
  if (emergency_stopped_ && coming_to_rest_ && robot_current) bring_to_rest();
  if (!robot_current) ++robot_stale_cycles_;
  const bool written = robot_current ? command_robot() : hardware_->hold() == robot::HardwareStatus::kOk;
  // a robot that refuses a command or cannot be read is a fault: hold what we have, report it
  if (!written || read == robot::HardwareStatus::kFault) {
    ++hardware_faults_;
    state_ = msg::STATE_FAULT;
  }
  record_metrics();
  publish_state();
}

void FollowerNode::fill_status(msg::NodeStatus& status) const {
  architecture_->fill_status(status);
}

void FollowerNode::active_faults(std::vector<uint32_t>& faults) const {
  if (hardware_faults_ > 0) faults.push_back(msg::FAULT_HARDWARE);
  if (reflex_.latched()) {
    faults.push_back(reflex_.fault_code());
  } else if (state_ == msg::STATE_SAFE_HOLD) {
    faults.push_back(hold_cause_);
  }
  if (validator_.rejected() > 0) faults.push_back(msg::FAULT_COMMAND_REJECTED);
}

void FollowerNode::fill_report(runtime::NodeReport& report) const {
  report.add(joint_commands_);
  // Cartesian commands are the exception (PFC): a topic nobody wrote to would only be noise
  if (cartesian_commands_.stats().received() > 0) report.add(cartesian_commands_);
  report.add(state_pub_);
  report.add(wrench_pub_);
  auto counter = [&](const char* name, double value) { report.counters.emplace_back(name, value); };
  counter("watchdog_trips", static_cast<double>(watchdog_trips_));
  counter("stall_holds", static_cast<double>(stall_holds_));
  counter("holds_awaiting_enable", static_cast<double>(holds_awaiting_enable_));
  counter("robot_state_holds", static_cast<double>(robot_state_holds_));
  counter("robot_stale_cycles", static_cast<double>(robot_stale_cycles_));
  hardware_->report_counters(report.counters);
  counter("liveliness_trips", static_cast<double>(liveliness_trips_));
  counter("watchdog_latency_max_ms", watchdog_latency_max_s_ * 1e3);
  counter("torque_saturations", static_cast<double>(limiter_.saturations()));
  counter("torque_rate_limited", static_cast<double>(limiter_.rate_limited()));
  counter("peak_torque_ratio", limiter_.peak_ratio());
  counter("torque_step_max_nm", limiter_.largest_step_nm());
  counter("hardware_faults", static_cast<double>(hardware_faults_));
  counter("mode_changes", static_cast<double>(mode_changes_));
  counter("tracking_rmse_rad", joint_tracking_.rms());
  counter("tracking_max_error_rad", joint_tracking_.max_abs());
  counter("cartesian_rmse_m", cartesian_tracking_.rms());
  counter("cartesian_max_error_m", cartesian_tracking_.max_abs());
  counter("observer_vs_hardware_rms_nm", observer_vs_hardware_.rms());
  counter("direct_vs_hardware_rms_nm", direct_vs_hardware_.rms());
  counter("peak_external_force_n", peak_external_force_n_);
  counter("peak_external_moment_nm", peak_external_moment_nm_);
  counter("peak_external_joint_torque_nm", peak_external_joint_torque_nm_);
  counter("command_sessions", static_cast<double>(command_sessions_));
  counter("rejoins", static_cast<double>(rejoin_.rejoins()));
  counter("reflex_trips", static_cast<double>(reflex_.trips()));
  counter("reflex_trip_ratio", reflex_.last_trip_ratio());
  // 0 none, 1 joint torque, 2 force, 3 moment, 4 joint velocity (safety_reflex.h, ReflexCause)
  counter("reflex_cause", static_cast<double>(reflex_.last_cause()));
  counter("reflex_peak_ratio", reflex_.peak_ratio());
  counter("reflex_latched", reflex_.latched() ? 1.0 : 0.0);
  counter("resets", static_cast<double>(resets_));
  architecture_->fill_report(report);
  for (size_t i = 0; i < static_cast<size_t>(CommandIssue::kCount); ++i) {
    const auto issue = static_cast<CommandIssue>(i);
    counter(to_string(issue), static_cast<double>(validator_.count(issue)));
  }
}

void FollowerNode::trace_columns(std::vector<std::string>& columns) const {
  for (const char* c : {"x_x", "x_y", "x_z", "f_ext_x", "f_ext_y", "f_ext_z", "f_est_x", "f_est_y", "f_est_z", "tdpa_w_j",
                        "tdpa_drift_m", "torque_ratio", "state", "cmd_session", "cmd_seq", "reflex", "reflex_ratio",
                        "tdpa_dissipated_j", "tdpa_acting"}) {
    columns.emplace_back(c);
  }
  for (size_t i = 0; i < config_.joints; ++i) columns.push_back("q_" + std::to_string(i));
}

void FollowerNode::trace_row(double* row) const {
  const Eigen::Vector3d& x = control_.ee_position();
  for (int i = 0; i < 3; ++i) *row++ = x[i];
  // the external force on the robot (the wall pushing back, simulation ground truth): what the operator should feel
  for (int i = 0; i < 3; ++i) *row++ = control_.hardware_wrench()[i];
  for (int i = 0; i < 3; ++i) *row++ = control_.wrench()[i];
  *row++ = architecture_->observed_energy_j();
  *row++ = architecture_->position_drift_m();
  *row++ = torque_ratio_;
  *row++ = static_cast<double>(state_);
  // which sender's command is in force (sessions counted from 1) and its number
  *row++ = static_cast<double>(command_sessions_);
  *row++ = static_cast<double>(command_seq_);
  // 0 while not latched, else what tripped it (the report's reflex_cause)
  *row++ = reflex_.latched() ? static_cast<double>(reflex_.last_cause()) : 0.0;
  // this cycle's largest load or speed against its threshold (over 1: the reflex must be latched)
  *row++ = reflex_.ratio();
  row = runtime::trace_tdpa_work(architecture_->tdpa(), row);
  std::copy_n(arm_.q_rad.begin(), config_.joints, row);
}

}  // namespace teleop::follower
