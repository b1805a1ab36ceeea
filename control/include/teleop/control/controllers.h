#pragma once
// Torque controllers of one 7-DoF arm (docs/control.md). compute() is real-time safe: no
// allocation, no exception, no lock. Every controller reads the rigid-body model through an
// ArmDynamics it shares with the others (updated at most once per state).

#include "teleop/control/arm_dynamics.h"
#include "teleop/control/types.h"

namespace teleop::control {

/// compute(state, command) -> joint torque [Nm], link side.
class Controller {
 public:
  virtual ~Controller() = default;
  virtual JointVector compute(const ArmState& state, const ArmCommand& command) = 0;
  virtual const char* name() const = 0;

 protected:
  Controller() = default;
  Controller(const Controller&) = default;
  Controller& operator=(const Controller&) = default;
};

/// tau = g(q): the arm floats, the command is ignored.
class GravityCompensation final : public Controller {
 public:
  explicit GravityCompensation(ArmDynamics& dynamics) : dyn_(&dynamics) {}
  JointVector compute(const ArmState& state, const ArmCommand& command) override;
  const char* name() const override { return "gravity_compensation"; }

 private:
  ArmDynamics* dyn_;
};

/// tau = K (q_d - q) + D (dq_d - dq) + g(q) + tau_ff, K and D diagonal.
class JointImpedance final : public Controller {
 public:
  struct Gains {
    JointVector stiffness;  ///< Nm/rad
    JointVector damping;    ///< Nm s/rad
  };
  JointImpedance(ArmDynamics& dynamics, const Gains& gains) : dyn_(&dynamics), gains_(gains) {}
  JointVector compute(const ArmState& state, const ArmCommand& command) override;
  const char* name() const override { return "joint_impedance"; }
  const Gains& gains() const { return gains_; }
  /// Real-time safe: the gains of each command (e.g. the stiffness the leader asks for).
  void set_gains(const Gains& gains) { gains_ = gains; }

 private:
  ArmDynamics* dyn_;
  Gains gains_;
};

/// PARTI eq. 4, task-space impedance with nullspace posture stiffness:
///   tau = J^T (K_x e + D_x (v_d - J dq)) + N (K_n (q_rest - q) - D_n dq) + n(q, dq)
/// (v_d the desired twist, zero for a pose set point)
/// e = (x_d - x, orientation error), the orientation error being the rotation vector of
/// R_d R^T (from the quaternion q_d q^-1, taken with w >= 0), world frame.
/// D_x = diag(2 zeta sqrt(k_i Lambda_ii)) with Lambda = (J M^-1 J^T)^-1 the task-space inertia
/// (its diagonal: a per-axis critically damped choice, not the full double diagonalisation).
/// N = I - J^T Lambda J M^-1, the dynamically consistent nullspace projector, so at rest the
/// nullspace torque never shifts the end effector: the static displacement is K_x^-1 F.
class CartesianImpedance final : public Controller {
 public:
  struct Gains {
    Eigen::Vector3d translational_stiffness{500, 500, 500};  ///< N/m
    Eigen::Vector3d rotational_stiffness{30, 30, 30};        ///< Nm/rad
    double damping_ratio = 1.0;
    JointVector nullspace_stiffness = JointVector::Constant(5);  ///< Nm/rad
    JointVector nullspace_damping = JointVector::Constant(1);    ///< Nm s/rad
    /// Tikhonov term added to J M^-1 J^T before inverting it (near singularities).
    double lambda_damping = 1e-6;
  };
  CartesianImpedance(ArmDynamics& dynamics, const Gains& gains) : dyn_(&dynamics), gains_(gains) {}
  JointVector compute(const ArmState& state, const ArmCommand& command) override;
  const char* name() const override { return "cartesian_impedance"; }
  const Gains& gains() const { return gains_; }
  /// Real-time safe: the gains of each command.
  void set_gains(const Gains& gains) { gains_ = gains; }
  /// Pose error of the last compute(): translation then rotation vector (world frame).
  const Vector6& last_error() const { return error_; }

 private:
  ArmDynamics* dyn_;
  Gains gains_;
  Vector6 error_ = Vector6::Zero();
};

/// Stiff joint PD without any model: tau = Kp (q_d - q) + Kd (dq_d - dq) + tau_ff. The
/// stand-in for Justin's "state space" controller (Justin report §3.5): it follows positions
/// hard and leaves a static error g(q)/Kp.
class PositionPd final : public Controller {
 public:
  struct Gains {
    JointVector kp;
    JointVector kd;
  };
  explicit PositionPd(const Gains& gains) : gains_(gains) {}
  JointVector compute(const ArmState& state, const ArmCommand& command) override;
  const char* name() const override { return "position_pd"; }

 private:
  Gains gains_;
};

}  // namespace teleop::control
