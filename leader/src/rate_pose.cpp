#include "rate_pose.h"

#include <algorithm>
#include <cmath>

namespace teleop::leader {

double RatePose::shaped(double deflection, double dead_band) {
  const double d = std::clamp(deflection, -1.0, 1.0);
  if (!(std::abs(d) > dead_band)) return 0.0;
  return std::copysign((std::abs(d) - dead_band) / (1.0 - dead_band), d);
}

void RatePose::step(const std::array<double, 6>& deflection) {
  for (int i = 0; i < 6; ++i) {
    const double speed = i < 3 ? config_.linear_speed_mps : config_.angular_speed_radps;
    twist_[i] = speed * shaped(deflection[static_cast<size_t>(i)], config_.dead_band);
  }
  x_ += twist_.head<3>() * period_s_;
  const Eigen::Vector3d w = twist_.tail<3>();
  const double angle = w.norm() * period_s_;
  // the angular velocity is in the base frame: the increment multiplies from the left; the
  // quaternion is renormalised so that hours of small steps stay a rotation
  if (angle > 0.0) q_ = (Eigen::Quaterniond(Eigen::AngleAxisd(angle, w / w.norm())) * q_).normalized();
}

}  // namespace teleop::leader
