#pragma once
// External joint torque and end-effector wrench estimators (PARTI eqs. 5-8, docs/control.md).
// update() is real-time safe: no allocation.

#include "teleop/control/arm_dynamics.h"
#include "teleop/control/types.h"

namespace teleop::control {

/// Generalised-momentum observer (PARTI eqs. 6-7, De Luca / Haddadin et al. 2017).
///
/// Derivation. M(q) ddq + C(q, dq) dq + g(q) = tau + tau_ext, p = M dq (eq. 6). With the
/// skew-symmetry property dM/dt = C + C^T,
///   dp/dt = dM/dt dq + M ddq = tau + tau_ext - C dq - g + (C + C^T) dq = tau + tau_ext - beta,
///   beta  = g - C^T dq = n - dM/dt dq,   n = C dq + g (MuJoCo's qfrc_bias).
/// So C^T dq never needs C itself: beta is the bias MuJoCo gives minus dM/dt dq. The observer
///   r(t) = K_O ( p(t) - p(0) - int_0^t (tau - beta + r) ds )                       (eq. 7)
/// obeys dr/dt = K_O (tau_ext - r): each joint's r is tau_ext through a first-order low-pass of
/// bandwidth k_O,i, without ddq.
///
/// Discretisation (cycle h, state k measured after the torque tau_{k-1} acted for one cycle):
///   I_k = I_{k-1} + h (tau_{k-1} - n_{k-1} + r_{k-1}) + (M_k - M_{k-1}) dq_k
///   r_k = K_O (M_k dq_k - p_0 - I_k)
/// The term (M_k - M_{k-1}) dq_k is the integral of dM/dt dq over the cycle. For a semi-implicit
/// Euler integrator (MuJoCo's, M_{k-1}(dq_k - dq_{k-1}) = h (tau + tau_ext - n_{k-1})) this makes
/// the momentum balance exact: r_k = r_{k-1} + h K_O (tau_ext - r_{k-1}); stable for h k_O < 2.
/// Whatever the model lacks (e.g. joint friction) shows up in r as external torque.
///
/// A robot on a network does not deliver one state per cycle: some cycles see none, the next one
/// the state of two cycles later. update() then takes the interval between the two measurements
/// (the robot's own stamps) as h, and the same measurement again changes nothing. Where h k_O > 1
/// (a gap of 10 ms at K_O = 100/s; the recursion would overshoot, and diverge past 2) r is the
/// interval's mean external torque, M_{k-1} (dq_k - dq_{k-1}) / h - (tau_{k-1} - n_{k-1}).
class MomentumObserver {
 public:
  /// `gain` is K_O's diagonal [1/s].
  MomentumObserver(ArmDynamics& dynamics, double cycle_s, const JointVector& gain);

  /// Next update() starts afresh (p_0 = its momentum, r = 0).
  void reset() { started_ = false; }

  /// `tau_applied`: the joint torque that acted over the last cycle (measured or commanded,
  /// link side). Returns r = the estimate of tau_ext.
  const JointVector& update(const ArmState& state, const JointVector& tau_applied) {
    return update(state, tau_applied, h_);
  }
  /// The same with the measurement `interval_s` after the last one (0: the same measurement).
  const JointVector& update(const ArmState& state, const JointVector& tau_applied, double interval_s);
  const JointVector& external_torque() const { return r_; }

 private:
  // where h k_O > 1: r is the interval's mean external torque
  void bridge_gap(const JointVector& p, const JointVector& dq, const JointVector& tau_applied, double interval_s);

  ArmDynamics* dyn_;
  double h_;
  JointVector gain_;
  bool started_ = false;
  JointVector p0_ = JointVector::Zero();
  JointVector integral_ = JointVector::Zero();
  JointVector r_ = JointVector::Zero();
  JointVector dq_prev_ = JointVector::Zero();
  JointMatrix mass_prev_ = JointMatrix::Zero();
  JointVector bias_prev_ = JointVector::Zero();
};

/// The direct estimator of Haddadin et al. 2017 *with* its inertial terms (not PARTI's eq. 5,
/// which drops them: PartiDirectEstimator):
///   tau_ext = M(q) ddq + n(q, dq) - tau,   ddq = (dq_k - dq_{k-1}) / h,
/// all at the current state, then low-passed: est = gamma tau_ext + (1 - gamma) est_prev.
/// It differentiates the velocity once more, so it suffers from velocity noise and lags by a
/// cycle what the observer gets from the momentum balance.
class DirectEstimator {
 public:
  DirectEstimator(ArmDynamics& dynamics, double cycle_s, double gamma);
  void reset() { started_ = false; }
  const JointVector& update(const ArmState& state, const JointVector& tau_applied) {
    return update(state, tau_applied, h_);
  }
  /// ddq over the measurement `interval_s` after the last one (0: the same measurement, no update).
  const JointVector& update(const ArmState& state, const JointVector& tau_applied, double interval_s);
  const JointVector& external_torque() const { return estimate_; }

 private:
  ArmDynamics* dyn_;
  double h_;
  double gamma_;
  bool started_ = false;
  JointVector dq_prev_ = JointVector::Zero();
  JointVector estimate_ = JointVector::Zero();
};

/// PARTI eq. 5, the estimator of Franka's Gazebo model (PARTI §3.2.1), with no inertial and no
/// Coriolis term:
///   tau_ext = tau_d - tau_m + g(q),   est = gamma tau_ext + (1 - gamma) est_prev,
/// tau_d the torque the control law commanded, tau_m the measured joint torque, g(q) gravity of
/// the estimator's model; est starts at 0 and its first update already filters (gamma in (0, 1]).
/// Signs as PARTI prints them. What the result means depends on what is fed as tau_d and tau_m
/// (docs/fidelity.md, "PARTI's direct estimator"): with tau_d = 0 and tau_m the link-side torque
/// tau_J it is g(q) - tau_J, the direct estimator above without M ddq + C dq, exact at rest and
/// off by -(M ddq + C dq) in motion.
class PartiDirectEstimator {
 public:
  /// Throws std::invalid_argument unless 0 < gamma <= 1.
  PartiDirectEstimator(ArmDynamics& dynamics, double gamma);
  void reset() { estimate_.setZero(); }
  /// Real-time safe. Updates `dynamics` at (q, 0) for g(q).
  const JointVector& update(const JointVector& q, const JointVector& tau_d, const JointVector& tau_m);
  const JointVector& external_torque() const { return estimate_; }

 private:
  ArmDynamics* dyn_;
  double gamma_;
  JointVector estimate_ = JointVector::Zero();
};

/// End-effector wrench from external joint torque (PARTI eq. 8, written there as J tau_ext; the
/// consistent map is the pseudo-inverse of J^T): F = (J J^T + mu^2 I)^-1 J tau_ext, J the
/// site Jacobian of `dynamics` at its last state (call dynamics.update() first). Force then
/// moment, world frame, at the site. Assumes the whole tau_ext comes from a wrench there.
Vector6 wrench_from_torque(const ArmDynamics& dynamics, const JointVector& tau_ext, double mu = 1e-3);

}  // namespace teleop::control
