#pragma once
// A minimum-jerk joint motion: every coordinate moves from its start to its goal along the
// quintic s(tau) = 10 tau^3 - 15 tau^4 + 6 tau^5, tau = t / T, so position, velocity and
// acceleration are continuous and the velocity and acceleration are zero at both ends (Flash and
// Hogan's minimum-jerk profile). The SVH study moves its arm and hand from "home" to "test" on it.

#include <cstddef>
#include <span>
#include <vector>

namespace teleop::hand {

class MinJerkMotion {
 public:
  /// Throws std::invalid_argument when the sizes differ or the duration is not positive.
  MinJerkMotion(std::vector<double> start, std::vector<double> goal, double duration_s);

  size_t size() const { return start_.size(); }
  double duration_s() const { return duration_s_; }
  /// Position and velocity at `t_s` (before 0: the start at rest; after T: the goal at rest)
  /// into `q` and `dq`, each of size(). Real-time safe.
  void sample(double t_s, std::span<double> q, std::span<double> dq) const;

 private:
  std::vector<double> start_;
  std::vector<double> goal_;
  double duration_s_;
};

}  // namespace teleop::hand
