#pragma once
// Where the SVH-class hand is in a MuJoCo model (config/models/svh_hand.xml, scene_ur5_svh.xml;
// docs/hand.md): its 20 joints, 9 motors, 11 coupling equalities and the index-tip touch sensor,
// found by name and checked against the coupling table of HandCoupling, which is the one source
// of truth for the factors and offsets (the model's equalities must agree with it).

#include <mujoco/mujoco.h>

#include <array>
#include <cstddef>
#include <string>

#include "teleop/hand/hand_coupling.h"

namespace teleop::hand {

/// The joint whose name is the motor's (its "main" joint: the one the motor's actuator drives).
/// Index into kHandJointNames.
size_t main_joint_of(size_t motor);

/// A coupled joint as a MuJoCo joint equality: q[joint] = c0 + c1 * q[main joint of its motor].
/// From q_j = f_j m + q0_j and q_main = f_main m + q0_main.
struct CouplingPolynomial {
  size_t joint = 0;       ///< the coupled joint (joint1 of the equality)
  size_t main_joint = 0;  ///< its motor's main joint (joint2)
  double c0_rad = 0.0;
  double c1 = 0.0;
};
CouplingPolynomial coupling_polynomial(const HandCoupling& coupling, size_t joint);

/// Indices of the hand in one mjModel. Arrays over joints are in kHandJointNames order, arrays
/// over motors in kHandMotorNames order.
struct SvhModelIndex {
  std::array<int, kHandJoints> joint_id{};
  std::array<int, kHandJoints> qpos{};  ///< index in qpos
  std::array<int, kHandJoints> dof{};   ///< index in qvel / qfrc_*
  std::array<int, kHandMotors> actuator{};
  /// Each motor's main joint, as main_joint_of() (looked up once, for the control loop).
  std::array<size_t, kHandMotors> main_joint{};
  /// The equality that ties a coupled joint to its main joint; -1 for the 9 main joints.
  std::array<int, kHandJoints> equality{};
  /// Range of each motor [rad, motor units] that keeps every joint it drives inside its own
  /// limits (the intersection of the joints' ranges mapped through the coupling).
  std::array<double, kHandMotors> motor_min_rad{};
  std::array<double, kHandMotors> motor_max_rad{};
  int tip_touch_address = -1;  ///< index in sensordata of index_tip_touch
};

/// Finds the hand in `m`. Throws std::runtime_error naming `model_name` and the element when a
/// joint, motor, equality or the touch sensor is missing, a joint is no limited hinge with qpos0
/// = 0, a motor drives another joint or with a gear other than 1, or an equality's joints or
/// polynomial differ from `coupling` (|difference| > 1e-12).
SvhModelIndex index_svh_model(const mjModel* m, const std::string& model_name, const HandCoupling& coupling);

}  // namespace teleop::hand
