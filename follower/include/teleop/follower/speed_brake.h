#pragma once
// After a joint-speed trip the arm is braked to a stop, not left to coast in the reflex's
// compliant hold. The brake takes a share of the whole arm's velocity per cycle,
// tau = -(share / cycle) M(q) dq: every mode of the coupled arm slows by the same share, so the
// explicit 1 kHz brake stays stable wherever the arm is. A per-joint damper D_i = share M_ii /
// cycle does not: where joints couple, the fastest mode of M^-1 D is max eig(S M^-1 S) times the
// share (S = diag(M)^1/2), 19 at the Panda's home pose and 32 with its shoulder near straight,
// so 0.2 of it removed 3.9 to 6.5 times the velocity each cycle; the torques saturated and the
// arm wandered along its null space to a joint limit (seen in a process test).
// The brake is scaled as a whole into the torque the drives have left, so it only ever takes
// energy out of the arm.

#include "teleop/common/joint_model.h"
#include "teleop/control/types.h"

namespace teleop::follower {

class SpeedBrake {
 public:
  /// `share_per_cycle` in [0, 1): the share of the velocity removed per cycle of `cycle_s`.
  SpeedBrake(double share_per_cycle, double cycle_s) : gain_per_s_(share_per_cycle / cycle_s) {}

  /// Adds the brake for velocity `dq` and inertia `mass` to `tau` (the hold's torques), scaled
  /// down as a whole where a joint would exceed `max_torque_nm`. Real-time safe.
  void apply(const control::JointMatrix& mass, const control::JointVector& dq, const JointVector& max_torque_nm,
             control::JointVector& tau) const;

 private:
  double gain_per_s_;
};

}  // namespace teleop::follower
