#pragma once
// The operator's plan for the two-arm box task (PARTI §3.3, docs/box_task.md): where the box is to
// be and how far each hand stands off its side face, at given times. Read once from YAML.

#include <Eigen/Core>
#include <string>
#include <vector>

namespace teleop::box_task {

/// The two hands; the left one presses the box's +y face, the right one its -y face.
enum class Side { kLeft = 0, kRight = 1 };
inline constexpr Side kSides[] = {Side::kLeft, Side::kRight};
inline const char* side_name(Side side) { return side == Side::kLeft ? "left" : "right"; }

/// One waypoint of the plan: both hands reach it at t_s, from the previous one on a straight line
/// with a minimum-jerk time law (at rest at every waypoint).
struct BoxWaypoint {
  std::string phase;      ///< what the step does (approach, squeeze, lift, ...), for people
  double t_s = 0;         ///< after the start at the "home" pose
  Eigen::Vector3d box_m;  ///< box centre the hands hold (robot base frame)
  double gap_m = 0;       ///< flange tip to side face along y; negative presses into the face
  /// The force the operator's hand adds on purpose at the flange [N]: towards the box face (the
  /// squeeze) and upwards (holding up its share of the box's weight). A person grasps by pressing
  /// and feels the result, so an operator in the loop squeezes with force, not with depth.
  double squeeze_n = 0;
  double lift_n = 0;
};

struct BoxPlan {
  std::string file;
  std::string left_model;     ///< left_arm.xml (one arm, robot base frame), resolved path
  std::string right_model;    ///< right_arm.xml
  std::string home_keyframe;  ///< the joints at t = 0 (the follower's and leader's start pose)
  double rate_hz = 100;       ///< rows per second of the written trajectories
  double box_half_width_m = 0.1;  ///< half the box along y (flange tip at face = centre +- this)
  double grip_height_m = 0;  ///< flange axis above the box centre (> 0: the box hangs below the grip)
  std::vector<BoxWaypoint> waypoints;  ///< strictly increasing times, the first after 0

  const std::string& model(Side side) const { return side == Side::kLeft ? left_model : right_model; }
  double duration_s() const { return waypoints.back().t_s; }
  /// Whether any waypoint asks for a force (the trajectories then carry the operator's torque).
  bool has_force() const;
};

/// Loads a plan. Throws ConfigError "<file>:<line>: <key>: <problem>" for a missing or unknown
/// key, a value out of range, or times that do not increase.
BoxPlan load_box_plan(const std::string& path);

/// Where `side`'s flange tip is at `waypoint`: beside the box face, grip_height_m above the centre.
Eigen::Vector3d hand_position(const BoxPlan& plan, const BoxWaypoint& waypoint, Side side);

/// The operator's intended force on `side`'s flange at `waypoint` (robot base frame): squeeze_n
/// towards the box face, lift_n up.
Eigen::Vector3d hand_force(const BoxWaypoint& waypoint, Side side);

}  // namespace teleop::box_task
