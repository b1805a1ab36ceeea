#pragma once
// The follower's commands joined without a step (common/joint_ramp.h): after a hold, a joint
// command's target is approached from the held pose at a bounded speed, its velocity and
// feed-forward left out until the reference has caught up. (Cartesian commands come in another
// mode than the joint hold: the controller switch blends their torque in, docs/control.md.)

#include "teleop/common/joint_ramp.h"
#include "teleop/follower/command_validator.h"

namespace teleop::follower {

/// Real-time safe: no allocation after construction.
class JointRejoin {
 public:
  JointRejoin(size_t joints, double max_speed_radps, double cycle_s) : ramp_(joints, max_speed_radps, cycle_s) {}

  /// Starts moving the reference from `held_rad`.
  void start(const JointVector& held_rad) { ramp_.start(held_rad); }
  /// Ends a rejoin (the robot holds again).
  void stop() { ramp_.stop(); }
  /// The command to control with this cycle: `command` itself once caught up (or not started),
  /// else `command` with its target replaced by the reference, one step closer, at rest.
  const ValidCommand& apply(const ValidCommand& command);
  bool active() const { return ramp_.active(); }
  /// Rejoins started so far.
  uint64_t rejoins() const { return ramp_.starts(); }

 private:
  JointRamp ramp_;
  ValidCommand ramped_{};
};

}  // namespace teleop::follower
