#include "box_plan.h"

#include "teleop/common/config.h"
#include "teleop/common/joint_config.h"

namespace teleop::box_task {

BoxPlan load_box_plan(const std::string& path) {
  const ConfigNode root = ConfigNode::load_file(path);
  BoxPlan plan;
  plan.file = path;
  const ConfigNode models = root.child("models");
  plan.left_model = models.get_path("left");
  plan.right_model = models.get_path("right");
  plan.home_keyframe = models.get_string("home_keyframe", "home");
  plan.rate_hz = root.get_double("rate_hz", {1, 1000});
  const ConfigNode box = root.child("box");
  plan.box_half_width_m = box.get_double("half_width_m", {0.01, 0.5});
  plan.grip_height_m = box.get_double("grip_height_m", {-0.5, 0.5});

  double previous_t_s = 0;
  for (const ConfigNode& node : root.get_node_list("waypoints")) {
    BoxWaypoint waypoint;
    waypoint.phase = node.get_string("phase");
    waypoint.t_s = node.get_double("t_s", {0, 600});
    if (waypoint.t_s <= previous_t_s) {
      throw node.error("t_s", "must be later than the previous waypoint's (" + std::to_string(previous_t_s) + " s)");
    }
    previous_t_s = waypoint.t_s;
    const auto centre = read_vector3(node, "box_m", {-3, 3});
    waypoint.box_m = {centre[0], centre[1], centre[2]};
    waypoint.gap_m = node.get_double("gap_m", {-0.05, 0.5});
    waypoint.squeeze_n = node.get_double("squeeze_n", {0, 100}, 0.0);
    waypoint.lift_n = node.get_double("lift_n", {-100, 100}, 0.0);
    plan.waypoints.push_back(waypoint);
  }
  if (plan.waypoints.empty()) throw root.error("waypoints", "needs at least one waypoint");
  root.check_all_used();
  return plan;
}

bool BoxPlan::has_force() const {
  for (const BoxWaypoint& w : waypoints) {
    if (w.squeeze_n != 0 || w.lift_n != 0) return true;
  }
  return false;
}

Eigen::Vector3d hand_force(const BoxWaypoint& waypoint, Side side) {
  const double towards_box = side == Side::kLeft ? -1.0 : 1.0;
  return {0, towards_box * waypoint.squeeze_n, waypoint.lift_n};
}

Eigen::Vector3d hand_position(const BoxPlan& plan, const BoxWaypoint& waypoint, Side side) {
  const double sign = side == Side::kLeft ? 1.0 : -1.0;
  return waypoint.box_m + Eigen::Vector3d(0, sign * (plan.box_half_width_m + waypoint.gap_m), plan.grip_height_m);
}

}  // namespace teleop::box_task
