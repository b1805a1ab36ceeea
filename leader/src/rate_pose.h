#pragma once
// A rate-controlled pose: how a 6-DoF mouse or a gamepad moves. The device's deflection (each of
// x y z, rx ry rz in [-1, 1], in the follower's base frame) is a velocity: past the dead band it is
// scaled to the full speed at full deflection and integrated into a pose about where it started,
//   v = v_max s(d),  w = w_max s(d),  x += v T,  R <- exp([w] T) R,
//   s(d) = sign(d) (|d| - b) / (1 - b) for |d| > b, else 0.
// The leader maps this pose like a haptic arm's flange (cartesian_mapping.h): its clutch, dead-man
// button and workspace box act on the command, not here.

#include <Eigen/Geometry>
#include <array>

#include "teleop/control/types.h"

namespace teleop::leader {

struct RatePoseConfig {
  /// Speeds at full deflection.
  double linear_speed_mps = 0.05;
  double angular_speed_radps = 0.3;
  /// The share of the deflection that reads as none (a cap or a stick at rest is never at 0).
  double dead_band = 0.1;
};

class RatePose {
 public:
  RatePose(const RatePoseConfig& config, double period_s) : config_(config), period_s_(period_s) {}

  /// One period. Real-time safe.
  void step(const std::array<double, 6>& deflection);

  /// The pose about the start (position [m], rotation) and the twist of this period (linear,
  /// then angular).
  const Eigen::Vector3d& position() const { return x_; }
  const Eigen::Quaterniond& orientation() const { return q_; }
  const control::Vector6& twist() const { return twist_; }

  /// The dead band's shaping of one component, clamped to [-1, 1]; NaN reads as rest.
  static double shaped(double deflection, double dead_band);

 private:
  RatePoseConfig config_;
  double period_s_;
  Eigen::Vector3d x_ = Eigen::Vector3d::Zero();
  Eigen::Quaterniond q_ = Eigen::Quaterniond::Identity();
  control::Vector6 twist_ = control::Vector6::Zero();
};

}  // namespace teleop::leader
