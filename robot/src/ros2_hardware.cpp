#include "ros2_hardware.h"

#include <limits>
#include <stdexcept>
#include <thread>

#include "teleop/common/clock.h"

namespace teleop::robot {

Ros2Hardware::Ros2Hardware(const Ros2HardwareConfig& config)
    : config_(config), name_("ros2:" + config.state_topic), link_(config) {
  wait_for_robot();
}

Ros2Hardware::~Ros2Hardware() {
  // the controller keeps applying the last command it got: make it the hold, and see it taken
  (void)hold();
  link_.flush(0.5);
}

void Ros2Hardware::wait_for_robot() {
  const int64_t give_up_ns = monotonic_now_ns() + static_cast<int64_t>(config_.connect_timeout_s * 1e9);
  const bool wants_wrench = !config_.wrench_topic.empty();
  bool have_state = false;
  bool have_wrench = false;
  while (monotonic_now_ns() < give_up_ns && !(have_state && (have_wrench || !wants_wrench) && link_.command_readers() > 0)) {
    have_state = link_.newest_state(state_) || have_state;
    have_wrench = link_.newest_wrench(wrench_) || have_wrench;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  const std::string waited = " within ros2.connect_timeout_s (" + std::to_string(config_.connect_timeout_s) +
                             " s) on domain " + std::to_string(config_.participant.domain_id);
  if (!have_state) {
    const std::string mismatch = link_.name_mismatch();
    if (!mismatch.empty()) throw std::runtime_error("the robot's " + config_.state_topic + " does not fit ros2.joints: " + mismatch);
    throw std::runtime_error("no sensor_msgs/JointState on " + config_.state_topic + waited);
  }
  if (wants_wrench && !have_wrench) {
    throw std::runtime_error("no geometry_msgs/WrenchStamped on " + config_.wrench_topic + waited +
                             (config_.wrench_frame.empty() ? "" : " in frame " + config_.wrench_frame));
  }
  if (link_.command_readers() == 0) {
    throw std::runtime_error("no controller subscribed to " + config_.command_topic + waited +
                             " (is the forward_command_controller active?)");
  }
  hold_q_rad_ = state_.q_rad;
}

HardwareStatus Ros2Hardware::read(ArmState& state) {
  (void)link_.newest_state(state_);
  (void)link_.newest_wrench(wrench_);
  // judged by arrival: a robot clock that differs from ours does not make a state fresh or stale
  const int64_t now_ns = monotonic_now_ns();
  state.q_rad = state_.q_rad;
  state.dq_radps = state_.dq_radps;
  state.tau_measured_nm = state_.tau_nm;
  state.tau_ext_nm = JointVector{};  // a JointState carries none: the follower's observer estimates it
  state.measured_ns = state_.stamp_ns;
  const bool wrench_fresh = !config_.wrench_topic.empty() &&
                            static_cast<double>(now_ns - wrench_.arrival_ns) * 1e-9 <= config_.state_timeout_s;
  state.force_ext_n = wrench_fresh ? wrench_.force_n : std::array<double, 3>{};
  state.torque_ext_nm = wrench_fresh ? wrench_.torque_nm : std::array<double, 3>{};
  state.wrench_measured = wrench_fresh;
  // a configured wrench is part of the state: without it the follower would see no load at all
  const bool fresh = static_cast<double>(now_ns - state_.arrival_ns) * 1e-9 <= config_.state_timeout_s &&
                     (config_.wrench_topic.empty() || wrench_fresh);
  return fresh ? HardwareStatus::kOk : HardwareStatus::kStale;
}

void Ros2Hardware::set_reference(const JointVector& q_rad, const JointVector& dq_radps) {
  q_ref_rad_ = q_rad;
  dq_ref_radps_ = dq_radps;
}

HardwareStatus Ros2Hardware::write(const JointVector& tau_nm) {
  holding_ = false;
  switch (config_.interface) {
    case Ros2CommandInterface::kEffort: return link_.send(tau_nm) ? HardwareStatus::kOk : HardwareStatus::kFault;
    case Ros2CommandInterface::kPosition: return link_.send(q_ref_rad_) ? HardwareStatus::kOk : HardwareStatus::kFault;
    case Ros2CommandInterface::kVelocity: return link_.send(dq_ref_radps_) ? HardwareStatus::kOk : HardwareStatus::kFault;
  }
  return HardwareStatus::kFault;
}

HardwareStatus Ros2Hardware::hold() {
  if (!holding_) hold_q_rad_ = state_.q_rad;  // the last pose the robot reported
  holding_ = true;
  // zero effort on the robot's gravity compensation, zero velocity, or the pose it was at
  const JointVector& command = config_.interface == Ros2CommandInterface::kPosition ? hold_q_rad_ : JointVector{};
  return link_.send(command) ? HardwareStatus::kOk : HardwareStatus::kFault;
}

int64_t Ros2Hardware::cycle_phase_ns() const {
  if (!config_.phase_lock || state_.arrival_ns == 0) return 0;
  return state_.arrival_ns + static_cast<int64_t>(config_.phase_lock_lead_s * 1e9);
}

void Ros2Hardware::report_counters(std::vector<std::pair<std::string, double>>& counters) const {
  counters.emplace_back("robot_states_refused", static_cast<double>(link_.invalid_states()));
  counters.emplace_back("robot_wrenches_refused", static_cast<double>(link_.invalid_wrenches()));
}

HardwareLimits Ros2Hardware::limits() const {
  constexpr double inf = std::numeric_limits<double>::infinity();
  HardwareLimits limits;
  limits.q_min_rad.fill(-inf);
  limits.q_max_rad.fill(inf);
  limits.max_torque_nm.fill(inf);
  for (size_t i = 0; i < config_.q_min_rad.size(); ++i) limits.q_min_rad[i] = config_.q_min_rad[i];
  for (size_t i = 0; i < config_.q_max_rad.size(); ++i) limits.q_max_rad[i] = config_.q_max_rad[i];
  for (size_t i = 0; i < config_.max_torque_nm.size(); ++i) limits.max_torque_nm[i] = config_.max_torque_nm[i];
  return limits;
}

}  // namespace teleop::robot
