#pragma once
// Rigid-body quantities of the arm for a given joint state, computed by MuJoCo on an mjData of
// its own, so computing them never disturbs a simulation running on the same model.

#include <mujoco/mujoco.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <string_view>

#include "teleop/control/types.h"

namespace teleop::control {

/// Mass matrix, bias forces, gravity, end-effector pose and Jacobian of a 7-DoF arm.
/// Construction allocates (an mjData) and throws; update() and the getters do not allocate.
/// The model must outlive this object and have exactly kDof degrees of freedom.
class ArmDynamics {
 public:
  /// Throws std::invalid_argument when the model's nv != kDof or it has no site `ee_site`.
  ArmDynamics(const mjModel* model, std::string_view ee_site);

  ArmDynamics(ArmDynamics&&) noexcept = default;
  ArmDynamics& operator=(ArmDynamics&&) noexcept = default;
  ArmDynamics(const ArmDynamics&) = delete;
  ArmDynamics& operator=(const ArmDynamics&) = delete;
  ~ArmDynamics() = default;

  /// Recomputes everything for (q, dq): mj_kinematics, mj_comPos, mj_crb (M including the
  /// rotor armature), mj_comVel + mj_rne with dq = 0 (gravity) and with dq (bias), mj_jacSite.
  /// Skips the work when (q, dq) equals the last state (several controllers, one cycle).
  void update(const ArmState& state);

  const ArmState& state() const { return state_; }
  /// Joint-space inertia M(q), armature on the diagonal.
  const JointMatrix& mass() const { return mass_; }
  /// n(q, dq) = C(q, dq) dq + g(q) (MuJoCo's qfrc_bias).
  const JointVector& bias() const { return bias_; }
  /// g(q): the bias at dq = 0.
  const JointVector& gravity() const { return gravity_; }
  const Eigen::Vector3d& ee_position() const { return ee_position_; }
  const Eigen::Matrix3d& ee_rotation() const { return ee_rotation_; }
  /// 6 x kDof site Jacobian, linear rows first, world frame.
  const Jacobian& jacobian() const { return jacobian_; }

  const mjModel* model() const { return model_; }
  int ee_site() const { return site_; }

 private:
  struct DataDeleter {
    void operator()(mjData* d) const noexcept { mj_deleteData(d); }
  };

  const mjModel* model_;
  std::unique_ptr<mjData, DataDeleter> data_;
  int site_;
  bool valid_ = false;
  ArmState state_;
  JointMatrix mass_ = JointMatrix::Zero();
  JointVector bias_ = JointVector::Zero();
  JointVector gravity_ = JointVector::Zero();
  Eigen::Vector3d ee_position_ = Eigen::Vector3d::Zero();
  Eigen::Matrix3d ee_rotation_ = Eigen::Matrix3d::Identity();
  Jacobian jacobian_ = Jacobian::Zero();
};

}  // namespace teleop::control
