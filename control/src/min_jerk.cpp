#include "teleop/control/min_jerk.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace teleop::control {

MinJerkMotion::MinJerkMotion(std::vector<double> start, std::vector<double> goal, double duration_s)
    : start_(std::move(start)), goal_(std::move(goal)), duration_s_(duration_s) {
  if (start_.size() != goal_.size()) throw std::invalid_argument("MinJerkMotion: start and goal differ in size");
  if (!(duration_s_ > 0.0) || !std::isfinite(duration_s_)) {
    throw std::invalid_argument("MinJerkMotion: the duration must be positive");
  }
}

void MinJerkMotion::sample(double t_s, std::span<double> q, std::span<double> dq) const {
  const double tau = std::clamp(t_s / duration_s_, 0.0, 1.0);
  const double s = min_jerk_progress(tau);
  const double ds = min_jerk_rate(tau) / duration_s_;
  for (size_t i = 0; i < start_.size(); ++i) {
    const double span = goal_[i] - start_[i];
    q[i] = start_[i] + span * s;
    dq[i] = span * ds;
  }
}

MinJerkPath::MinJerkPath(std::vector<double> start) : start_(std::move(start)) {
  if (start_.empty()) throw std::invalid_argument("MinJerkPath: an empty start");
}

void MinJerkPath::then(std::vector<double> waypoint, double duration_s) {
  // a copy: emplace_back may move the motion whose goal this is
  std::vector<double> from = motions_.empty() ? start_ : motions_.back().goal();
  motions_.emplace_back(std::move(from), std::move(waypoint), duration_s);
  begins_s_.push_back(duration_s_);
  duration_s_ += duration_s;
}

void MinJerkPath::sample(double t_s, std::span<double> q, std::span<double> dq) const {
  if (motions_.empty()) {
    std::copy(start_.begin(), start_.end(), q.begin());
    std::fill(dq.begin(), dq.begin() + static_cast<ptrdiff_t>(start_.size()), 0.0);
    return;
  }
  // the last motion that has begun (the first before it has)
  size_t i = 0;
  while (i + 1 < motions_.size() && t_s >= begins_s_[i + 1]) ++i;
  motions_[i].sample(t_s - begins_s_[i], q, dq);
}

}  // namespace teleop::control
