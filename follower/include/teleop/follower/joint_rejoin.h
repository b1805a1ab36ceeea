#pragma once
// Joining a command stream without a step. When joint commands resume after a hold (the first
// command of a run, a restarted leader, the end of an outage or a reset reflex), their target may
// lie far from the pose the robot holds; the follower then moves its reference from the held
// pose towards the commanded one at a bounded joint speed, and follows the command itself once
// the reference has caught up with it. (Cartesian commands come in another mode than the joint
// hold: the controller switch blends their torque in, docs/control.md.)

#include "teleop/common/joint_model.h"
#include "teleop/follower/command_validator.h"

namespace teleop::follower {

/// Real-time safe: no allocation after construction.
class JointRejoin {
 public:
  JointRejoin(size_t joints, double max_speed_radps, double cycle_s)
      : joints_(joints), max_step_rad_(max_speed_radps * cycle_s) {}

  /// Starts moving the reference from `held_rad`.
  void start(const JointVector& held_rad);
  /// Ends a rejoin (the robot holds again).
  void stop() { active_ = false; }
  /// The command to control with this cycle: `command` itself once caught up (or not started),
  /// else `command` with its target replaced by the reference, one step closer, at rest.
  const ValidCommand& apply(const ValidCommand& command);
  bool active() const { return active_; }
  /// Rejoins started so far.
  uint64_t rejoins() const { return rejoins_; }

 private:
  size_t joints_;
  double max_step_rad_;
  bool active_ = false;
  uint64_t rejoins_ = 0;
  JointVector reference_rad_{};
  ValidCommand ramped_{};
};

}  // namespace teleop::follower
