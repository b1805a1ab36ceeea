#include "robot_arm_device.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace teleop::leader {

RobotArmDevice::RobotArmDevice(std::unique_ptr<robot::RobotHardware> arm, std::unique_ptr<ArmKinematics> gravity,
                               const JointVector& max_torque_nm, const JointVector& damping_nms_per_rad)
    : arm_(std::move(arm)),
      gravity_(std::move(gravity)),
      name_(std::string("robot_arm:") + arm_->name()),
      damping_(damping_nms_per_rad) {
  if (!arm_->compensates_gravity() && !gravity_) {
    throw std::invalid_argument(std::string("the arm ") + arm_->name() +
                                " does not carry its own weight: the device needs its model for g(q)");
  }
  const robot::HardwareLimits limits = arm_->limits();
  for (size_t k = 0; k < arm_->joints(); ++k) limit_nm_[k] = std::min(limits.max_torque_nm[k], max_torque_nm[k]);
}

bool RobotArmDevice::read(DeviceState& state) {
  const robot::HardwareStatus status = arm_->read(state_);
  current_ = status == robot::HardwareStatus::kOk;
  if (!current_) {
    ++(status == robot::HardwareStatus::kFault ? fault_reads_ : stale_reads_);
    return false;
  }
  state.q_rad = state_.q_rad;
  state.dq_radps = state_.dq_radps;
  // what acts on the arm from outside is the operator's hand (the robot's estimate, or the truth)
  state.tau_operator_nm = state_.tau_ext_nm;
  if (gravity_) gravity_->update(state_.q_rad, state_.dq_radps);
  return true;
}

bool RobotArmDevice::write(const JointVector& feedback_nm) {
  if (!current_) {
    // no torque from a state that is not current: the robot holds by itself until it is
    ++holds_;
    return arm_->hold() == robot::HardwareStatus::kOk;
  }
  bool clamped = false;
  for (size_t k = 0; k < arm_->joints(); ++k) {
    const double weight = gravity_ ? gravity_->gravity()[static_cast<Eigen::Index>(k)] : 0.0;
    const double wanted = (std::isfinite(feedback_nm[k]) ? feedback_nm[k] : 0.0) + weight - damping_[k] * state_.dq_radps[k];
    torque_nm_[k] = std::clamp(wanted, -limit_nm_[k], limit_nm_[k]);
    clamped = clamped || torque_nm_[k] != wanted;
  }
  if (clamped) ++torque_clamps_;
  return arm_->write(torque_nm_) == robot::HardwareStatus::kOk;
}

void RobotArmDevice::report_counters(std::vector<std::pair<std::string, double>>& counters) const {
  arm_->report_counters(counters);
  counters.emplace_back("arm_stale_reads", static_cast<double>(stale_reads_));
  counters.emplace_back("arm_fault_reads", static_cast<double>(fault_reads_));
  counters.emplace_back("arm_torque_clamps", static_cast<double>(torque_clamps_));
  counters.emplace_back("arm_holds", static_cast<double>(holds_));
}

}  // namespace teleop::leader
