#pragma once
// The last stage before the motors: per-joint torque saturation and a torque rate limit (a step
// in commanded torque is what excites the structure and what a real drive rejects, e.g. the
// Franka interface at 1000 Nm/s). Both always on, each clipping counted.

#include <cstddef>
#include <cstdint>

#include "teleop/common/joint_model.h"

namespace teleop::follower {

class TorqueLimiter {
 public:
  /// `max_rate_nm_per_s` infinite (or <= 0): no rate limit.
  TorqueLimiter(size_t joints, const JointVector& max_torque_nm, double max_rate_nm_per_s, double cycle_s);

  /// Limits `tau` in place (total link-side torque). Real-time safe. `rate_limit` false: only
  /// the saturation (a latched reflex brakes at once: a real drive would refuse such a step and
  /// stop the arm itself, which is the same outcome; this arm has only us to stop it).
  void apply(JointVector& tau, bool rate_limit = true);
  /// The next apply() starts from `tau` (e.g. the torque the robot holds at start).
  void reset(const JointVector& tau) {
    last_ = tau;
    started_ = true;
  }

  uint64_t saturations() const { return saturations_; }
  uint64_t rate_limited() const { return rate_limited_; }
  /// Largest |tau_i| / max_torque_i seen after limiting (<= 1 by construction).
  double peak_ratio() const { return peak_ratio_; }
  /// Largest change of any joint's torque from one apply() to the next [Nm].
  double largest_step_nm() const { return largest_step_; }

 private:
  size_t joints_;
  JointVector max_torque_;
  double max_step_;
  bool started_ = false;
  JointVector last_{};
  uint64_t saturations_ = 0;
  uint64_t rate_limited_ = 0;
  double peak_ratio_ = 0.0;
  double largest_step_ = 0.0;
};

}  // namespace teleop::follower
