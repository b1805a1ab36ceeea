#pragma once
// A payload on the flange (a tool, a gripper, a held part) and a joint-torque bias: what the
// follower's model of the arm lacks, identified from static poses (payload_identification.h) and
// stored per robot (docs/calibration.md). Its weight is a wrench at the end-effector site; the
// joint torque it puts on the arm is linear in (m, m c), which is what makes it identifiable.

#include <Eigen/Core>

#include "teleop/control/arm_dynamics.h"
#include "teleop/control/types.h"

namespace teleop::control {

struct Payload {
  double mass_kg = 0.0;
  /// Centre of mass in the frame of the end-effector site.
  Eigen::Vector3d com_m = Eigen::Vector3d::Zero();
};

/// What a calibration found: the payload, and a constant offset of the external-torque estimate
/// (sensor offsets, model error the poses could not tell from a load).
struct ArmCalibration {
  Payload payload;
  JointVector torque_bias_nm = JointVector::Zero();
};

/// 6 x 4 map from (m, m c_x, m c_y, m c_z) to the payload's weight as a wrench at the site
/// (force; moment about the site; world frame), for the site's rotation and gravity vector.
Eigen::Matrix<double, 6, 4> payload_wrench_map(const Eigen::Matrix3d& site_rotation, const Eigen::Vector3d& gravity);

/// The joint torque the payload's weight exerts on the arm at `dynamics`' last state: J^T w
/// (what an external-torque estimator sees of an unmodelled payload). Real-time safe.
JointVector payload_torque(const ArmDynamics& dynamics, const Payload& payload);

}  // namespace teleop::control
