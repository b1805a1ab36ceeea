#include "teleop/follower/torque_limiter.h"

#include <algorithm>
#include <cmath>

namespace teleop::follower {

TorqueLimiter::TorqueLimiter(size_t joints, const JointVector& max_torque_nm, double max_rate_nm_per_s, double cycle_s)
    : joints_(joints), max_torque_(max_torque_nm), max_step_(max_rate_nm_per_s > 0 ? max_rate_nm_per_s * cycle_s : 0.0) {}

void TorqueLimiter::apply(JointVector& tau, bool rate_limit) {
  for (size_t i = 0; i < joints_; ++i) {
    double t = tau[i];
    if (rate_limit && max_step_ > 0 && started_) {
      const double limited = std::clamp(t, last_[i] - max_step_, last_[i] + max_step_);
      if (limited != t) ++rate_limited_;
      t = limited;
    }
    const double saturated = std::clamp(t, -max_torque_[i], max_torque_[i]);
    if (saturated != t) ++saturations_;
    tau[i] = saturated;
    if (started_) largest_step_ = std::max(largest_step_, std::abs(saturated - last_[i]));
    last_[i] = saturated;
    peak_ratio_ = std::max(peak_ratio_, std::abs(saturated) / max_torque_[i]);
  }
  started_ = true;
}

}  // namespace teleop::follower
