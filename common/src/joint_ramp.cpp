#include "teleop/common/joint_ramp.h"

#include <algorithm>
#include <cmath>

namespace teleop {

void JointRamp::start(const JointVector& held_rad) {
  reference_rad_ = held_rad;
  active_ = true;
  ++starts_;
}

bool JointRamp::step(const JointVector& target_rad) {
  if (!active_) return false;
  bool caught_up = true;
  for (size_t i = 0; i < joints_; ++i) {
    const double gap = target_rad[i] - reference_rad_[i];
    if (std::abs(gap) > max_step_rad_) caught_up = false;
    reference_rad_[i] += std::clamp(gap, -max_step_rad_, max_step_rad_);
  }
  active_ = !caught_up;
  return active_;
}

}  // namespace teleop
