#pragma once
// Kinematics of the arm class the leader device and the follower share (the same 7-DoF arm,
// the same base frame): end-effector pose and twist for joint angles, J^T F to render a wrench
// as joint torques and its least-squares inverse to express rendered torques as a wrench.
// Setup loads the model (throws naming the file); everything after is real-time safe.

#include <string>

#include "teleop/common/joint_model.h"
#include "teleop/control/arm_dynamics.h"
#include "teleop/sim/mujoco_model.h"

namespace teleop::leader {

class ArmKinematics {
 public:
  ArmKinematics(const std::string& model_path, const std::string& ee_site);

  /// Recomputes pose, Jacobian and twist for (q, dq) (the first 7 joints).
  void update(const JointVector& q_rad, const JointVector& dq_radps);

  const Eigen::Vector3d& position() const { return dynamics_.ee_position(); }
  const Eigen::Matrix3d& rotation() const { return dynamics_.ee_rotation(); }
  /// Linear then angular velocity of the end effector (base frame).
  const control::Vector6& twist() const { return twist_; }
  /// g(q): the joint torques that carry the arm's own weight.
  const control::JointVector& gravity() const { return dynamics_.gravity(); }
  /// tau = J^T wrench: the joint torques that exert `wrench` (force, moment) at the end effector.
  void torque_for_wrench(const control::Vector6& wrench, JointVector& tau_nm) const;
  /// The wrench that joint torques `tau_nm` exert at the end effector (damped least squares).
  control::Vector6 wrench_for_torque(const JointVector& tau_nm) const;

 private:
  sim::MujocoModel model_;
  control::ArmDynamics dynamics_;
  control::ArmState state_;
  control::Vector6 twist_ = control::Vector6::Zero();
};

}  // namespace teleop::leader
