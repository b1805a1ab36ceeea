#include "teleop/follower/speed_brake.h"

#include <algorithm>
#include <cmath>

namespace teleop::follower {

void SpeedBrake::apply(const control::JointMatrix& mass, const control::JointVector& dq,
                       const JointVector& max_torque_nm, control::JointVector& tau) const {
  const control::JointVector brake = -gain_per_s_ * (mass * dq);
  // one scale for all joints keeps the brake's direction, and so its power -s dq' M dq, negative
  double scale = 1.0;
  for (Eigen::Index i = 0; i < brake.size(); ++i) {
    const double max = max_torque_nm[static_cast<size_t>(i)];
    // the room the brake has in this joint: up to the limit on its side of zero
    const double room = std::signbit(brake[i]) == std::signbit(tau[i]) ? max - std::abs(tau[i]) : max + std::abs(tau[i]);
    // a joint the hold alone saturates is clipped by the limiter either way
    if (room <= 0.0) continue;
    if (std::abs(brake[i]) > room) scale = std::min(scale, room / std::abs(brake[i]));
  }
  tau += scale * brake;
}

}  // namespace teleop::follower
