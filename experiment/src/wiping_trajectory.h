#pragma once
// The wiping study's plan as a trajectory of the hand: the tool's path over the panel (three
// wipes: down, across, up, over to the next) made for an assumed wiper pose and panel height,
// turned into set points of the hand frame through that assumed pose. Executed in a world where
// the wiper sits at another angle or the panel at another height, the same hand motion puts the
// tool somewhere else: the thesis replayed its real robot's plan the same way (§4.4.1).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <utility>
#include <vector>

#include "teleop/control/types.h"
#include "teleop/experiment/wiping_study.h"

namespace teleop::experiment {

/// The panel's surface as the plan assumes it: its centre and frame (world).
struct PanelFrame {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  Eigen::Vector3d u = Eigen::Vector3d::UnitY();  ///< across, horizontal
  Eigen::Vector3d v = Eigen::Vector3d::UnitX();  ///< up the slope
  Eigen::Vector3d n = Eigen::Vector3d::UnitZ();  ///< outward normal
};

/// A hand set point: pose and twist (linear then angular, world frame).
struct HandSetPoint {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  control::Vector6 twist = control::Vector6::Zero();
};

class WipingTrajectory {
 public:
  /// `tool_in_hand`: the tool site's pose in the hand frame for the planned wiper angle;
  /// `hand_start`: where the hand is at t = 0. Allocates.
  WipingTrajectory(const WipingPlan& plan, const PanelFrame& panel, const Eigen::Isometry3d& tool_in_hand,
                   const Eigen::Isometry3d& hand_start);

  /// The set point at `t_s` (minimum jerk along each segment; the last pose after the end).
  HandSetPoint at(double t_s) const;
  double duration_s() const { return segments_.empty() ? 0.0 : segments_.back().t0_s + segments_.back().length_s; }
  /// Each wipe's window [begin, end]: from the press down to the end of the lift.
  const std::vector<std::pair<double, double>>& wipe_windows() const { return windows_; }
  /// The tool's orientation the plan holds over the panel (world).
  const Eigen::Matrix3d& tool_rotation() const { return tool_rotation_; }

 private:
  struct Segment {
    double t0_s;
    double length_s;
    Eigen::Vector3d from;
    Eigen::Vector3d to;
    Eigen::Quaterniond q_from;
    Eigen::Quaterniond q_to;
  };
  void add(double length_s, const Eigen::Vector3d& to, const Eigen::Quaterniond& q_to);

  std::vector<Segment> segments_;
  std::vector<std::pair<double, double>> windows_;
  Eigen::Matrix3d tool_rotation_ = Eigen::Matrix3d::Identity();
};

}  // namespace teleop::experiment
