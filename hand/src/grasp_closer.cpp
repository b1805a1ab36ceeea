#include "teleop/hand/grasp_closer.h"

#include <algorithm>

namespace teleop::hand {

GraspCloserConfig power_grasp(const HandMotorVector& closed_rad) {
  GraspCloserConfig g;
  g.closed_rad = closed_rad;
  g.by_feel.fill(true);
  g.closed_rad[hand_motor::kThumbOpposition] = 0.9;
  g.by_feel[hand_motor::kThumbOpposition] = false;
  g.closed_rad[hand_motor::kFingerSpread] = 0.0;
  g.by_feel[hand_motor::kFingerSpread] = false;
  g.squeeze_rad = 0.04;
  g.current_limit_a.fill(1.0);
  g.current_limit_a[hand_motor::kThumbFlexion] = 1.5;
  g.current_limit_a[hand_motor::kThumbOpposition] = 1.5;
  return g;
}

void GraspCloser::start(const HandMotorVector& from_rad) {
  from_ = from_rad;
  target_ = from_rad;
  contact_.fill(false);
  contact_rad_.fill(0.0);
  last_t_s_ = 0.0;
}

const HandMotorVector& GraspCloser::update(double t_s, const HandMotorVector& measured_rad) {
  const GraspCloserConfig& c = config_;
  const double dt = std::max(0.0, t_s - last_t_s_);
  last_t_s_ = t_s;
  for (size_t k = 0; k < kHandMotors; ++k) {
    if (!c.by_feel[k]) {
      // the hand's shape: straight to the closed angle at the closing speed
      const double step = c.closing_speed_radps * dt;
      target_[k] += std::clamp(c.closed_rad[k] - target_[k], -step, step);
      continue;
    }
    if (t_s < c.shape_time_s) continue;
    const double direction = c.closed_rad[k] >= from_[k] ? 1.0 : -1.0;
    if (contact_[k]) continue;
    // met something: the finger no longer follows its target
    if (std::abs(target_[k] - measured_rad[k]) > c.contact_lag_rad) {
      contact_[k] = true;
      contact_rad_[k] = measured_rad[k];
      target_[k] = measured_rad[k] + direction * c.squeeze_rad;
      continue;
    }
    const double step = c.closing_speed_radps * dt;
    target_[k] += std::clamp(c.closed_rad[k] - target_[k], -step, step);
  }
  return target_;
}

}  // namespace teleop::hand
