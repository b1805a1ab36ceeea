#pragma once
// A minimum-jerk joint motion: every coordinate moves from its start to its goal along the
// quintic s(tau) = 10 tau^3 - 15 tau^4 + 6 tau^5, tau = t / T, so position, velocity and
// acceleration are continuous and the velocity and acceleration are zero at both ends (Flash and
// Hogan's minimum-jerk profile). A path strings such motions through waypoints, stopping at each.
// The SVH study moves its arm and hand from "home" to "test" on one, the fidelity and PARTI studies
// their arms, the wiping study its tool (through the normalised profile).

#include <cstddef>
#include <span>
#include <vector>

namespace teleop::control {

/// The normalised profile s(tau) = 10 tau^3 - 15 tau^4 + 6 tau^5 for tau in [0, 1] (0 to 1).
inline double min_jerk_progress(double tau) { return tau * tau * tau * (10.0 - 15.0 * tau + 6.0 * tau * tau); }
/// Its rate ds/dtau = 30 tau^2 (1 - tau)^2.
inline double min_jerk_rate(double tau) { return 30.0 * tau * tau * (1.0 - tau) * (1.0 - tau); }


class MinJerkMotion {
 public:
  /// Throws std::invalid_argument when the sizes differ or the duration is not positive.
  MinJerkMotion(std::vector<double> start, std::vector<double> goal, double duration_s);

  size_t size() const { return start_.size(); }
  double duration_s() const { return duration_s_; }
  const std::vector<double>& goal() const { return goal_; }
  /// Position and velocity at `t_s` (before 0: the start at rest; after T: the goal at rest)
  /// into `q` and `dq`, each of size(). Real-time safe.
  void sample(double t_s, std::span<double> q, std::span<double> dq) const;

 private:
  std::vector<double> start_;
  std::vector<double> goal_;
  double duration_s_;
};

/// Minimum-jerk motions from one waypoint to the next, each starting when the one before ends.
class MinJerkPath {
 public:
  /// Starts at rest at `start`. Throws std::invalid_argument for an empty start.
  explicit MinJerkPath(std::vector<double> start);
  /// Appends a motion to `waypoint` taking `duration_s` (> 0; throws as MinJerkMotion).
  void then(std::vector<double> waypoint, double duration_s);

  size_t size() const { return start_.size(); }
  /// The time the last motion ends (0 without motions).
  double duration_s() const { return duration_s_; }
  /// Position and velocity at `t_s`: the start before 0, the last waypoint at rest after the end.
  /// Real-time safe.
  void sample(double t_s, std::span<double> q, std::span<double> dq) const;

 private:
  std::vector<double> start_;
  std::vector<MinJerkMotion> motions_;
  std::vector<double> begins_s_;  // when each motion starts
  double duration_s_ = 0.0;
};

}  // namespace teleop::control
