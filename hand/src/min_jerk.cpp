#include "teleop/hand/min_jerk.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace teleop::hand {

MinJerkMotion::MinJerkMotion(std::vector<double> start, std::vector<double> goal, double duration_s)
    : start_(std::move(start)), goal_(std::move(goal)), duration_s_(duration_s) {
  if (start_.size() != goal_.size()) throw std::invalid_argument("MinJerkMotion: start and goal differ in size");
  if (!(duration_s_ > 0.0) || !std::isfinite(duration_s_)) {
    throw std::invalid_argument("MinJerkMotion: the duration must be positive");
  }
}

void MinJerkMotion::sample(double t_s, std::span<double> q, std::span<double> dq) const {
  const double tau = std::clamp(t_s / duration_s_, 0.0, 1.0);
  const double tau2 = tau * tau;
  // s and ds/dt of the quintic; ds/dtau = 30 tau^2 (1 - tau)^2
  const double s = tau2 * tau * (10.0 - 15.0 * tau + 6.0 * tau2);
  const double ds = 30.0 * tau2 * (1.0 - tau) * (1.0 - tau) / duration_s_;
  for (size_t i = 0; i < start_.size(); ++i) {
    const double span = goal_[i] - start_[i];
    q[i] = start_[i] + span * s;
    dq[i] = span * ds;
  }
}

}  // namespace teleop::hand
