#pragma once
// Fixed-size types of the arm controllers: one 7-DoF arm (docs/control.md).

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace teleop::control {

/// Joints of the arm. Every vector and matrix is sized at compile time, so no update allocates.
inline constexpr int kDof = 7;

using JointVector = Eigen::Matrix<double, kDof, 1>;
using JointMatrix = Eigen::Matrix<double, kDof, kDof>;
/// Rows 0-2 linear (world frame), rows 3-5 angular (world frame).
using Jacobian = Eigen::Matrix<double, 6, kDof>;
using Vector6 = Eigen::Matrix<double, 6, 1>;
using Matrix6 = Eigen::Matrix<double, 6, 6>;

/// Measured joint state.
struct ArmState {
  JointVector q = JointVector::Zero();
  JointVector dq = JointVector::Zero();
};

/// What every controller may read; each uses its own part (see the controllers).
struct ArmCommand {
  // joint space: joint impedance, position PD
  JointVector q_d = JointVector::Zero();
  JointVector dq_d = JointVector::Zero();
  JointVector tau_ff = JointVector::Zero();
  // task space: Cartesian impedance (end-effector site, world frame)
  Eigen::Vector3d x_d = Eigen::Vector3d::Zero();
  Eigen::Quaterniond orientation_d = Eigen::Quaterniond::Identity();
  /// Desired twist (linear then angular, world frame); zero for a pose set point.
  Vector6 twist_d = Vector6::Zero();
  /// Rest posture the Cartesian impedance pulls towards in its nullspace.
  JointVector q_rest = JointVector::Zero();
};

}  // namespace teleop::control
