#pragma once
// The static poses of a payload calibration (docs/calibration.md), driven on the robot with the
// follower's own controller: each pose is approached once from above and once from below (by
// `approach_rad` on every joint), so that the joints' static friction, which holds the arm a
// little short of where gravity would put it, pulls the two estimates apart by equal and opposite
// amounts and cancels in their mean; the momentum observer's estimate is averaged while the arm
// rests there. The samples go to control::identify_payload.

#include <vector>

#include "teleop/control/min_jerk.h"
#include "teleop/control/payload_identification.h"
#include "teleop/follower/arm_control.h"
#include "teleop/robot/robot_hardware.h"

namespace teleop::follower {

struct PayloadCalibrationPlan {
  /// Poses that turn the flange through gravity about several axes (at least 2; 6 or more).
  std::vector<control::JointVector> poses;
  double move_s = 3.0;       ///< from one pose to the next (minimum jerk)
  double approach_s = 1.0;   ///< from the offset into the pose
  double settle_s = 1.0;     ///< at rest before measuring: the observer's and the arm's transients
  double measure_s = 0.5;    ///< averaging window
  double approach_rad = 0.05;
  double stiffness_nm_per_rad = 400.0;  ///< the joint impedance that holds each pose
  double damping_nms_per_rad = 40.0;
};

class PayloadCalibration {
 public:
  /// Plans the motion from the robot's current pose. Throws std::invalid_argument for a plan
  /// with fewer than 2 poses or non-positive times. Setup time.
  PayloadCalibration(robot::RobotHardware& hardware, ArmControl& control, const PayloadCalibrationPlan& plan,
                     double period_s);

  /// One control cycle: read, estimate, command, write. False once every pose was measured (the
  /// arm then holds the last one) or when the robot failed. Real-time safe.
  bool cycle();
  /// The measured poses so far, each the mean of its two approaches: the momentum observer's
  /// estimate, as it sees the arm (what identify_payload fits).
  std::vector<control::PayloadSample> samples() const;
  /// The same means of the external torque the follower publishes (ArmControl::external_torque(),
  /// a calibration applied): what is left of a payload once calibrated.
  std::vector<control::PayloadSample> published_samples() const;
  /// Seconds the whole plan takes.
  double duration_s() const { return path_.duration_s(); }
  /// Poses measured so far (both approaches).
  size_t poses_done() const;
  bool robot_failed() const { return failed_; }

 private:
  struct Window {
    double begin_s;
    double end_s;
    size_t pose;
  };
  void accumulate(double t_s);

  robot::RobotHardware& hardware_;
  ArmControl& control_;
  double period_s_;
  control::MinJerkPath path_;
  std::vector<Window> windows_;
  // per pose: summed estimate and joint angles over both windows, and the count
  std::vector<control::PayloadSample> means(const std::vector<control::JointVector>& sums) const;

  std::vector<control::JointVector> tau_sum_;
  std::vector<control::JointVector> published_sum_;
  std::vector<control::JointVector> q_sum_;
  std::vector<size_t> counts_;
  size_t cycle_ = 0;
  bool failed_ = false;
  robot::ArmState arm_;
  ValidCommand command_;
  JointVector max_torque_nm_{};
  std::vector<double> q_buffer_;
  std::vector<double> dq_buffer_;
};

}  // namespace teleop::follower
