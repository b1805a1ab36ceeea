#include "teleop/follower/safety_reflex.h"

#include <teleop/msg/status.h>

#include <algorithm>
#include <cmath>

namespace teleop::follower {

JointVector SafetyReflexConfig::filled(double rest, std::initializer_list<double> first) {
  JointVector v{};
  v.fill(rest);
  std::copy(first.begin(), first.end(), v.begin());
  return v;
}

ReflexCause SafetyReflex::largest(const control::JointVector& tau_ext_nm, const control::Vector6& wrench,
                                  const control::JointVector& dq_radps, double& ratio) const {
  // a NaN counts as infinitely far over: an estimator or sensor that fails is no reason to go on
  ReflexCause cause = ReflexCause::kNone;
  ratio = 0.0;
  const auto consider = [&](double value, double threshold, ReflexCause kind) {
    const double r = std::isnan(value) ? INFINITY : std::abs(value) / threshold;
    if (r > ratio) {
      cause = kind;
      ratio = r;
    }
  };
  for (Eigen::Index i = 0; i < tau_ext_nm.size(); ++i) {
    const auto j = static_cast<size_t>(i);
    consider(tau_ext_nm[i], config_.joint_torque_nm[j], ReflexCause::kJointTorque);
    consider(dq_radps[i], config_.joint_velocity_radps[j], ReflexCause::kJointVelocity);
  }
  for (Eigen::Index i = 0; i < 3; ++i) {
    const auto axis = static_cast<size_t>(i);
    consider(wrench[i], config_.force_n[axis], ReflexCause::kForce);
    consider(wrench[i + 3], config_.torque_nm[axis], ReflexCause::kTorque);
  }
  return cause;
}

bool SafetyReflex::check(const control::JointVector& tau_ext_nm, const control::Vector6& wrench,
                         const control::JointVector& dq_radps) {
  if (!config_.enabled) return false;
  double ratio = 0.0;
  const ReflexCause cause = largest(tau_ext_nm, wrench, dq_radps, ratio);
  ratio_ = ratio;
  peak_ratio_ = std::max(peak_ratio_, ratio);
  if (latched_ || ratio <= 1.0) return false;
  latched_ = true;
  ++trips_;
  cause_ = cause;
  trip_ratio_ = ratio;
  return true;
}

uint32_t SafetyReflex::fault_code() const {
  return cause_ == ReflexCause::kJointVelocity ? msg::FAULT_SPEED_REFLEX : msg::FAULT_CONTACT_REFLEX;
}

const char* to_string(ReflexCause cause) {
  switch (cause) {
    case ReflexCause::kNone: return "none";
    case ReflexCause::kJointTorque: return "joint_torque";
    case ReflexCause::kForce: return "force";
    case ReflexCause::kTorque: return "torque";
    case ReflexCause::kJointVelocity: return "joint_velocity";
  }
  return "?";
}

}  // namespace teleop::follower
