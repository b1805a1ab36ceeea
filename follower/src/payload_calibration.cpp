#include "teleop/follower/payload_calibration.h"

#include <algorithm>
#include <stdexcept>

namespace teleop::follower {
namespace {

std::vector<double> as_waypoint(const control::JointVector& q) { return {q.data(), q.data() + q.size()}; }

control::JointVector first_joints(const JointVector& v) { return Eigen::Map<const control::JointVector>(v.data()); }

}  // namespace

PayloadCalibration::PayloadCalibration(robot::RobotHardware& hardware, ArmControl& control,
                                       const PayloadCalibrationPlan& plan, double period_s)
    : hardware_(hardware), control_(control), period_s_(period_s), path_({0.0}) {
  if (plan.poses.size() < 2) throw std::invalid_argument("a payload calibration needs at least 2 poses");
  if (plan.move_s <= 0 || plan.approach_s <= 0 || plan.settle_s < 0 || plan.measure_s <= 0) {
    throw std::invalid_argument("a payload calibration's times must be positive");
  }
  if (hardware_.read(arm_) == robot::HardwareStatus::kFault) throw std::runtime_error("the robot hardware cannot be read");
  path_ = control::MinJerkPath(as_waypoint(first_joints(arm_.q_rad)));
  const control::JointVector offset = control::JointVector::Constant(plan.approach_rad);
  for (size_t p = 0; p < plan.poses.size(); ++p) {
    for (const double side : {1.0, -1.0}) {
      path_.then(as_waypoint(plan.poses[p] + side * offset), side > 0 ? plan.move_s : plan.approach_s);
      path_.then(as_waypoint(plan.poses[p]), plan.approach_s);
      const double at_rest_s = path_.duration_s();
      path_.then(as_waypoint(plan.poses[p]), plan.settle_s + plan.measure_s);  // stays
      windows_.push_back({at_rest_s + plan.settle_s, path_.duration_s(), p});
    }
  }
  tau_sum_.assign(plan.poses.size(), control::JointVector::Zero());
  published_sum_.assign(plan.poses.size(), control::JointVector::Zero());
  q_sum_.assign(plan.poses.size(), control::JointVector::Zero());
  counts_.assign(plan.poses.size(), 0);
  command_.mode = msg::CONTROL_JOINT_IMPEDANCE;
  command_.stiffness.fill(0.0);
  command_.damping.fill(0.0);
  std::fill_n(command_.stiffness.begin(), control::kDof, plan.stiffness_nm_per_rad);
  std::fill_n(command_.damping.begin(), control::kDof, plan.damping_nms_per_rad);
  max_torque_nm_ = hardware_.limits().max_torque_nm;
  q_buffer_.resize(control::kDof);
  dq_buffer_.resize(control::kDof);
}

bool PayloadCalibration::cycle() {
  const double t_s = static_cast<double>(cycle_++) * period_s_;
  if (t_s > path_.duration_s() || failed_) return false;
  const robot::HardwareStatus read = hardware_.read(arm_);
  if (read == robot::HardwareStatus::kFault) {
    failed_ = true;
    return false;
  }
  control_.estimate(arm_);
  accumulate(t_s);
  path_.sample(t_s, q_buffer_, dq_buffer_);
  std::copy(q_buffer_.begin(), q_buffer_.end(), command_.q_des_rad.begin());
  std::copy(dq_buffer_.begin(), dq_buffer_.end(), command_.dq_des_radps.begin());
  control::JointVector tau = control_.compute(arm_, command_);
  if (hardware_.compensates_gravity()) tau -= control_.gravity();
  JointVector out{};
  for (int i = 0; i < control::kDof; ++i) {
    const size_t k = static_cast<size_t>(i);
    out[k] = std::clamp(tau[i], -max_torque_nm_[k], max_torque_nm_[k]);
  }
  if (hardware_.write(out) == robot::HardwareStatus::kFault) failed_ = true;
  return !failed_;
}

void PayloadCalibration::accumulate(double t_s) {
  for (const Window& w : windows_) {
    if (t_s < w.begin_s || t_s >= w.end_s) continue;
    tau_sum_[w.pose] += control_.observer_torque();
    published_sum_[w.pose] += control_.external_torque();
    q_sum_[w.pose] += first_joints(arm_.q_rad);
    ++counts_[w.pose];
  }
}

std::vector<control::PayloadSample> PayloadCalibration::means(const std::vector<control::JointVector>& sums) const {
  std::vector<control::PayloadSample> out;
  for (size_t p = 0; p < counts_.size(); ++p) {
    if (counts_[p] == 0) continue;
    const double n = static_cast<double>(counts_[p]);
    out.push_back({q_sum_[p] / n, sums[p] / n});
  }
  return out;
}

std::vector<control::PayloadSample> PayloadCalibration::samples() const { return means(tau_sum_); }

std::vector<control::PayloadSample> PayloadCalibration::published_samples() const { return means(published_sum_); }

size_t PayloadCalibration::poses_done() const {
  const double t_s = static_cast<double>(cycle_) * period_s_;
  const auto ended = std::count_if(windows_.begin(), windows_.end(), [&](const Window& w) { return w.end_s <= t_s; });
  return static_cast<size_t>(ended) / 2;  // two approaches per pose
}

}  // namespace teleop::follower
