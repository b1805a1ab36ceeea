#include "teleop/follower/contact_reflex.h"

#include <algorithm>
#include <cmath>

namespace teleop::follower {

JointVector ContactReflexConfig::filled(double rest, std::initializer_list<double> first) {
  JointVector v{};
  v.fill(rest);
  std::copy(first.begin(), first.end(), v.begin());
  return v;
}

ReflexCause ContactReflex::over_threshold(const control::JointVector& tau_ext_nm, const control::Vector6& wrench,
                                          double& ratio) const {
  // the largest excess decides the cause; NaN estimates trip too (an estimator that fails is no
  // reason to trust the contact)
  ReflexCause cause = ReflexCause::kNone;
  ratio = 0.0;
  const auto consider = [&](double value, double threshold, ReflexCause kind) {
    const double r = std::abs(value) / threshold;
    if (std::isnan(value) || r > 1.0) {
      if (cause == ReflexCause::kNone || r > ratio || std::isnan(value)) {
        cause = kind;
        ratio = std::isnan(value) ? INFINITY : r;
      }
    }
  };
  for (Eigen::Index i = 0; i < tau_ext_nm.size(); ++i) {
    consider(tau_ext_nm[i], config_.joint_torque_nm[static_cast<size_t>(i)], ReflexCause::kJointTorque);
  }
  for (Eigen::Index i = 0; i < 3; ++i) {
    consider(wrench[i], config_.force_n[static_cast<size_t>(i)], ReflexCause::kForce);
    consider(wrench[i + 3], config_.torque_nm[static_cast<size_t>(i)], ReflexCause::kTorque);
  }
  return cause;
}

bool ContactReflex::check(const control::JointVector& tau_ext_nm, const control::Vector6& wrench) {
  if (!config_.enabled || latched_) return false;
  double ratio = 0.0;
  const ReflexCause cause = over_threshold(tau_ext_nm, wrench, ratio);
  if (cause == ReflexCause::kNone) return false;
  latched_ = true;
  ++trips_;
  cause_ = cause;
  trip_ratio_ = ratio;
  return true;
}

const char* to_string(ReflexCause cause) {
  switch (cause) {
    case ReflexCause::kNone: return "none";
    case ReflexCause::kJointTorque: return "joint_torque";
    case ReflexCause::kForce: return "force";
    case ReflexCause::kTorque: return "torque";
  }
  return "?";
}

}  // namespace teleop::follower
