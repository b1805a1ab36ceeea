#pragma once
// Inverse kinematics of one arm's flange by damped least squares on the ArmDynamics Jacobian,
// with a nullspace pull towards a rest posture and the joints kept inside their limits.

#include <mujoco/mujoco.h>

#include <Eigen/Geometry>
#include <string_view>

#include "teleop/control/arm_dynamics.h"

namespace teleop::box_task {

struct IkSettings {
  double damping = 0.02;           ///< lambda of (J J^T + lambda^2 I)^-1
  double nullspace_gain = 0.2;     ///< fraction of (q_rest - q) taken per iteration, in the nullspace
  int iterations = 10;             ///< fixed, so the result is reproducible
  double limit_margin_rad = 0.05;  ///< joints are held this far inside their ranges
};

/// Pose error left after solve(): position [m] and rotation angle [rad].
struct IkError {
  double position_m = 0;
  double rotation_rad = 0;
};

class HandIk {
 public:
  /// `arm` (nv == 7, e.g. left_arm.xml) must outlive this object; `ee_site` is its flange site.
  HandIk(const mjModel* arm, std::string_view ee_site, const control::JointVector& q_rest, const IkSettings& settings);

  /// Moves `q_rad` (the seed, e.g. the previous sample's solution) towards the flange pose
  /// (position_m, rotation), both in the arm model's world frame.
  IkError solve(const Eigen::Vector3d& position_m, const Eigen::Matrix3d& rotation, control::JointVector& q_rad);

  /// Flange pose for joints q (forward kinematics).
  Eigen::Isometry3d flange_pose(const control::JointVector& q_rad);

  /// The joint torque that exerts `force_n` (world frame) at the flange at joints q: J^T f.
  control::JointVector joint_torque(const control::JointVector& q_rad, const Eigen::Vector3d& force_n);
  /// Smallest distance of q to the model's joint range, over the joints [rad].
  double limit_distance(const control::JointVector& q_rad) const;

 private:
  control::Vector6 pose_error(const Eigen::Vector3d& position_m, const Eigen::Matrix3d& rotation) const;

  control::ArmDynamics dynamics_;
  control::JointVector q_rest_;
  control::JointVector q_min_;
  control::JointVector q_max_;
  IkSettings settings_;
};

}  // namespace teleop::box_task
