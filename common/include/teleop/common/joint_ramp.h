#pragma once
// Joining a stream of joint targets without a step. After a hold, a stream that resumes (the first
// command of a run, a restarted sender, the end of an outage, a reset) may aim far from where the
// robot holds; the reference then travels from the held pose towards the target at a bounded
// joint speed, and the target itself is used once the reference has caught up with it. Used by
// the follower for its commands and by the twin for the robot it is coupled to.

#include <cstddef>
#include <cstdint>

#include "teleop/common/joint_model.h"

namespace teleop {

/// Real-time safe: no allocation after construction.
class JointRamp {
 public:
  JointRamp(size_t joints, double max_speed_radps, double cycle_s)
      : joints_(joints), max_step_rad_(max_speed_radps * cycle_s) {}

  /// Starts the reference at `held_rad`.
  void start(const JointVector& held_rad);
  /// Ends a ramp (the robot holds again).
  void stop() { active_ = false; }
  /// Moves the reference one cycle towards `target_rad`. True while it has not caught up: use
  /// reference() this cycle; false once it has (or when not started): use the target.
  bool step(const JointVector& target_rad);

  const JointVector& reference() const { return reference_rad_; }
  bool active() const { return active_; }
  /// Ramps started so far.
  uint64_t starts() const { return starts_; }

 private:
  size_t joints_;
  double max_step_rad_;
  bool active_ = false;
  uint64_t starts_ = 0;
  JointVector reference_rad_{};
};

}  // namespace teleop
