#pragma once
// The plan turned into what the simulated operator pulls each haptic device along: one joint
// trajectory per hand, sampled at the plan's rate, solved by HandIk on left_arm.xml / right_arm.xml,
// written as the CSV the leader's `recorded` operator motion reads (t_s, q_0..q_6, and the torque
// the operator adds on purpose, tau_op_0..6, when the plan asks for hand forces).

#include <array>
#include <string>
#include <vector>

#include "box_plan.h"
#include "hand_ik.h"

namespace teleop::box_task {

struct HandTrajectory {
  Side side = Side::kLeft;
  std::vector<double> t_s;                  ///< 0, 1/rate, ... up to the last waypoint
  std::vector<control::JointVector> q_rad;  ///< one row per time
  /// The operator's intended torque per row (J^T of the plan's hand force at q_rad); empty when
  /// the plan asks for no force.
  std::vector<control::JointVector> tau_nm;
  IkError worst;                            ///< largest pose error left by the IK, over the rows
  double min_limit_distance_rad = 0;        ///< closest any joint came to its range's end
};

/// Both hands' flange poses along the plan: from the "home" keyframe pose at t = 0 straight to
/// each waypoint in turn, minimum-jerk in time; the flange keeps facing the box (its z axis along
/// -y for the left hand, +y for the right), turned there from "home" during the first segment.
/// Throws (naming the model file) when a model or its keyframe cannot be loaded.
std::array<HandTrajectory, 2> plan_hand_trajectories(const BoxPlan& plan, const IkSettings& settings = {});

/// Writes `t_s,q_0..q_6` rows (12 decimals), and tau_op_0..6 (the leader's intended-torque
/// columns, 9 decimals) when the trajectory has torques. Throws std::runtime_error naming `path` when it
/// cannot be written.
void write_trajectory_csv(const HandTrajectory& trajectory, const std::string& path);

}  // namespace teleop::box_task
