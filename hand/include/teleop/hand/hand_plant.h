#pragma once
// The SVH-class hand simulated in MuJoCo as a plant its 9 motors drive: torque in on each motor
// channel, motor and joint angles out, the index fingertip's contact force, and the state of the
// mechanical coupling. The model may be the hand alone (svh_hand.xml) or a scene that carries it
// (scene_ur5_svh.xml); what else the scene holds (an arm) its owner drives through model()/data().
// docs/hand.md.

#include <string>

#include "teleop/hand/hand_coupling.h"
#include "teleop/hand/svh_model.h"
#include "teleop/sim/mujoco_model.h"

namespace teleop::hand {

class HandPlant {
 public:
  /// Takes the loaded model and indexes the hand in it (throws as index_svh_model, e.g. when the
  /// model's equalities disagree with `coupling`; std::runtime_error when the model's integrator
  /// is not Euler, which the split step needs).
  HandPlant(sim::MujocoModel model, const HandCoupling& coupling);

  // --- one control step (real-time safe: no allocation) ---
  // begin_step(), then read the state and set the torques, then end_step(): the controller acts
  // on the state of this very step (its bias forces included), as MuJoCo's mj_step1/mj_step2
  // split allows for the Euler integrator the models use.
  /// Computes what depends on positions and velocities (mj_step1): qfrc_bias for this state.
  void begin_step();
  /// The torque [N m] of motor k at its main joint; MuJoCo clamps it to the actuator's range.
  void set_motor_torque(size_t motor, double torque_nm);
  /// Integrates over one model timestep with the torques set (mj_step2).
  void end_step();

  /// Motor angles m = (q_main - q0_main) / f_main [rad], and their rates.
  HandMotorVector motor_positions() const;
  HandMotorVector motor_velocities() const;
  /// The 20 joint angles / rates in kHandJointNames order.
  HandJointVector joint_positions() const;
  double joint_velocity(size_t joint) const;
  /// The normal contact force inside the index fingertip's zone [N] (its touch sensor).
  double tip_force_n() const;
  /// max over the coupled joints of |q_j - (c0 + c1 q_main)| [rad]: how far the simulated
  /// mechanism is from the coupling table.
  double coupling_residual_rad() const;
  /// Warnings MuJoCo counted in this data so far (instability, contact buffer full, ...): 0 in
  /// a sound run.
  int mujoco_warnings() const;

  // --- setup (may allocate) ---
  /// Switches the 11 coupling equalities on or off (mjModel::eq_active).
  void set_couplings_active(bool active);
  bool couplings_active() const;
  /// Gives every body a hand joint moves the diagonal inertia diag(I, I, I) about its centre of
  /// mass (masses unchanged; the SVH study's "inertia of the finger links") and recomputes
  /// MuJoCo's derived constants (mj_setConst).
  void set_link_inertia(double inertia_kgm2);
  /// The inertia [kg m^2] motor k's main joint feels at the current state (mj_forward done):
  /// through the couplings, s^T M s with s the joint motion per unit main-joint motion; without
  /// them the main joint's own, joint_inertia_kgm2().
  double channel_inertia_kgm2(size_t motor, bool through_couplings) const;
  /// The inertia one hand joint feels with every other joint free: 1 / (M^-1)_jj.
  double joint_inertia_kgm2(size_t joint) const;
  /// The torque limit [N m] of motor k's actuator (its ctrlrange, symmetric).
  double motor_torque_limit_nm(size_t motor) const;
  /// Sets every motor's torque limit to +-`limit_nm` (> 0; the actuators' ctrlrange).
  void set_motor_torque_limit(double limit_nm);

  const SvhModelIndex& index() const { return index_; }
  const HandCoupling& coupling() const { return coupling_; }
  const sim::MujocoModel& mujoco() const { return model_; }
  sim::MujocoModel& mujoco() { return model_; }
  mjModel* model() { return model_.model(); }
  const mjModel* model() const { return model_.model(); }
  mjData* data() { return model_.data(); }
  const mjData* data() const { return model_.data(); }

 private:
  sim::MujocoModel model_;
  HandCoupling coupling_;
  SvhModelIndex index_;
  std::array<CouplingPolynomial, kHandJoints> polynomial_{};  // c0 + c1 q_main per coupled joint
};

}  // namespace teleop::hand
