#pragma once
// The robot a twin arm is coupled to in real-time mode (PARTI eq. 2's q_phys): the newest joint
// angles it published, whether they are fresh, and the state that follows. When it comes back
// after a hold (a restarted leader starts at its home pose, wherever the twin held), the angles
// the twin is pulled to travel there from the held ones at a bounded speed (common/joint_ramp.h),
// so that neither the twin nor the follower it commands snaps across. Setup allocates (the
// reader); update() does not.

#include <teleop/msg/arm.h>
#include <teleop/msg/status.h>

#include "teleop/common/joint_model.h"
#include "teleop/common/joint_ramp.h"
#include "teleop/transport/participant.h"
#include "teleop/transport/subscription.h"

namespace teleop::twin {

class CoupledRobot {
 public:
  /// Reads `topic`; the angles start at `start_rad` (the twin's own pose: no pull before a sample).
  /// After a hold they join the robot's at `rejoin_speed_radps` (cycles of `cycle_s`).
  CoupledRobot(transport::Participant& participant, const transport::TopicSpec<msg::JointState>& topic, size_t joints,
               double peer_timeout_s, const JointVector& start_rad, double rejoin_speed_radps, double cycle_s);

  /// Takes what arrived: a sample with the wrong joint count is rejected (counted) and the last
  /// angles kept. Returns whether the robot is fresh and moves `state` accordingly: running while
  /// fresh, safe hold once a running robot lapsed. `stalled`: the twin's own loop missed more than
  /// the timeout (common/stall_watch.h): a hold for this cycle, so that the newest angles of the
  /// backlog are joined from the held ones, not stepped to. Real-time safe.
  bool update(int64_t now_ns, msg::NodeState& state, bool stalled = false);

  /// The angles to pull the twin to: the robot's, or on the way there after a hold.
  const JointVector& q_rad() const { return ramp_.active() ? ramp_.reference() : q_rad_; }
  uint64_t rejoins() const { return ramp_.starts(); }
  uint64_t rejected() const { return rejected_; }
  const transport::Subscription<msg::JointState>& subscription() const { return sub_; }

 private:
  transport::Subscription<msg::JointState> sub_;
  size_t joints_;
  int64_t timeout_ns_;
  JointVector q_rad_;
  JointRamp ramp_;
  uint64_t rejected_ = 0;
};

}  // namespace teleop::twin
