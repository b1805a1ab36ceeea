#include "teleop/follower/follower_node.h"

#include <algorithm>
#include <cmath>

#include "teleop/common/joint_config.h"
#include "teleop/follower/simple_hardware.h"
#include "teleop/transport/joint_fields.h"

namespace teleop::follower {
FollowerConfig FollowerNode::parse_config(const ConfigNode& root) {
  const ConfigNode s = root.child("follower");
  FollowerConfig c;
  const size_t n = read_joint_count(s);
  c.joints = n;
  const std::string hardware = s.get_choice("hardware", {"simple", "mujoco"}, "simple");
  c.hardware = hardware == "mujoco" ? FollowerConfig::Hardware::kMujoco : FollowerConfig::Hardware::kSimple;
  // both sections may stay in the file; each is checked, the chosen one is used
  if (auto model = s.optional_child("model")) c.model = read_joint_model(*model, n);
  c.model.joints = n;
  if (auto mujoco = s.optional_child("mujoco")) {
    c.mujoco.model_path = mujoco->get_path("model");
    c.mujoco.keyframe = mujoco->get_string("keyframe", "");
  }
  if (c.hardware == FollowerConfig::Hardware::kMujoco && c.mujoco.model_path.empty()) {
    throw s.error("mujoco", "hardware: mujoco needs a mujoco section with the model file");
  }
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

namespace {

std::unique_ptr<RobotHardware> make_hardware(const FollowerConfig& config, double rate_hz) {
  if (config.hardware == FollowerConfig::Hardware::kSimple) {
    return std::make_unique<SimpleHardware>(config.model, config.home_rad, 1.0 / rate_hz, config.wrench_lever_m);
  }
  MujocoHardwareConfig mujoco = config.mujoco;
  mujoco.period_s = 1.0 / rate_hz;
  auto hardware = std::make_unique<MujocoHardware>(mujoco);
  if (hardware->joints() != config.joints) {
    throw std::runtime_error("follower.joints is " + std::to_string(config.joints) + " but " + mujoco.model_path +
                             " drives " + std::to_string(hardware->joints()) + " joints");
  }
  return hardware;
}

}  // namespace

FollowerNode::FollowerNode(const FollowerConfig& config, runtime::NodeContext& context)
    : config_(config),
      hardware_(make_hardware(config, context.node.rate_hz)),
      validator_(config.joints, config.limits),
      command_(context.participant, transport::topics::kLeaderCommand),
      state_pub_(context.participant, transport::topics::kFollowerState, context.node.name),
      wrench_pub_(context.participant, transport::topics::kFollowerWrench, context.node.name) {
  auto& st = state_pub_.sample();
  st.robot(hardware_->name());
  st.arm("single");
  transport::presize_joint_state(st, config.joints);
  wrench_pub_.sample().frame("base");
  // until a command arrives, hold the pose the robot is in
  if (hardware_->read(arm_) != HardwareStatus::kOk) throw std::runtime_error("the robot hardware cannot be read");
  active_.q_des_rad = arm_.q_rad;
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
  // a hardware fault is not cleared by commands arriving: it needs an operator
  if (state_ == msg::STATE_FAULT) return;
  const bool fresh = have_command_ && now_ns - last_valid_command_ns_ < static_cast<int64_t>(config_.command_timeout_s * 1e9);
  if (fresh) {
    state_ = msg::STATE_RUNNING;
    return;
  }
  if (state_ == msg::STATE_RUNNING) {
    // commands stopped: hold the pose we are at, softly, until they come back
    state_ = msg::STATE_SAFE_HOLD;
    ++watchdog_trips_;
    std::copy_n(arm_.q_rad.begin(), config_.joints, active_.q_des_rad.begin());
    active_.dq_des_radps.fill(0.0);
    active_.tau_ff_nm.fill(0.0);
    active_.stiffness.fill(config_.hold_stiffness_nm_per_rad);
    active_.damping.fill(config_.hold_damping_nms_per_rad);
  }
}

void FollowerNode::compute_torque() {
  const auto& q = arm_.q_rad;
  const auto& dq = arm_.dq_radps;
  const double limit = config_.limits.max_torque_nm;
  for (size_t i = 0; i < config_.joints; ++i) {
    const double tau = active_.stiffness[i] * (active_.q_des_rad[i] - q[i]) +
                       active_.damping[i] * (active_.dq_des_radps[i] - dq[i]) + active_.tau_ff_nm[i];
    // torque saturation per joint, always
    tau_nm_[i] = std::clamp(tau, -limit, limit);
    if (tau_nm_[i] != tau) ++torque_saturations_;
  }
}

void FollowerNode::publish_state() {
  const size_t n = config_.joints;
  auto& st = state_pub_.sample();
  transport::copy_joints(arm_.q_rad, n, st.q_rad());
  transport::copy_joints(arm_.dq_radps, n, st.dq_radps());
  transport::copy_joints(arm_.tau_measured_nm, n, st.tau_measured_nm());
  transport::copy_joints(arm_.tau_ext_nm, n, st.tau_ext_nm());
  state_pub_.publish();

  const auto& f = arm_.force_ext_n;
  peak_external_force_n_ = std::max(peak_external_force_n_, std::sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]));
  auto& w = wrench_pub_.sample();
  w.force_n().x(arm_.force_ext_n[0]);
  w.force_n().y(arm_.force_ext_n[1]);
  w.force_n().z(arm_.force_ext_n[2]);
  w.torque_nm().x(arm_.torque_ext_nm[0]);
  w.torque_nm().y(arm_.torque_ext_nm[1]);
  w.torque_nm().z(arm_.torque_ext_nm[2]);
  wrench_pub_.publish();
}

void FollowerNode::cycle(const CycleTick& tick) {
  take_command(tick.now_ns);
  run_watchdog(tick.now_ns);
  compute_torque();
  // a robot that refuses a command or cannot be read is a fault: hold what we have, report it
  if (hardware_->write(tau_nm_) != HardwareStatus::kOk || hardware_->read(arm_) != HardwareStatus::kOk) {
    ++hardware_faults_;
    state_ = msg::STATE_FAULT;
  }
  publish_state();
}

void FollowerNode::active_faults(std::vector<uint32_t>& faults) const {
  if (hardware_faults_ > 0) faults.push_back(msg::FAULT_HARDWARE);
  if (state_ == msg::STATE_SAFE_HOLD) faults.push_back(msg::FAULT_STALE_INPUT);
  if (validator_.rejected() > 0) faults.push_back(msg::FAULT_COMMAND_REJECTED);
}

void FollowerNode::fill_report(runtime::NodeReport& report) const {
  report.add(command_);
  report.add(state_pub_);
  report.add(wrench_pub_);
  report.counters.emplace_back("watchdog_trips", static_cast<double>(watchdog_trips_));
  report.counters.emplace_back("torque_saturations", static_cast<double>(torque_saturations_));
  report.counters.emplace_back("hardware_faults", static_cast<double>(hardware_faults_));
  report.counters.emplace_back("peak_external_force_n", peak_external_force_n_);
  for (size_t i = 0; i < static_cast<size_t>(CommandIssue::kCount); ++i) {
    const auto issue = static_cast<CommandIssue>(i);
    report.counters.emplace_back(to_string(issue), static_cast<double>(validator_.count(issue)));
  }
}

}  // namespace teleop::follower
