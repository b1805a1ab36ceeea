#include "hand_trajectories.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>

#include "teleop/sim/mujoco_model.h"

namespace teleop::box_task {
namespace {

using control::JointVector;

/// Minimum-jerk time law: 0 -> 1 with zero velocity and acceleration at both ends.
double minimum_jerk(double tau) { return tau * tau * tau * (10.0 - 15.0 * tau + 6.0 * tau * tau); }

/// A flange pose, and the operator's force on it, at a waypoint of the path.
struct Pose {
  double t_s;
  Eigen::Vector3d position_m;
  Eigen::Quaterniond rotation;
  Eigen::Vector3d force_n = Eigen::Vector3d::Zero();
};

/// `home` turned (by the smallest rotation) so that the flange's z axis points at the box.
Eigen::Quaterniond facing_the_box(const Eigen::Matrix3d& home, Side side) {
  const Eigen::Vector3d towards_box(0, side == Side::kLeft ? -1.0 : 1.0, 0);
  return Eigen::Quaterniond::FromTwoVectors(home.col(2), towards_box) * Eigen::Quaterniond(home);
}

std::vector<Pose> flange_waypoints(const BoxPlan& plan, Side side, const Eigen::Isometry3d& home) {
  const Eigen::Quaterniond facing = facing_the_box(home.linear(), side);
  std::vector<Pose> poses{{0.0, home.translation(), Eigen::Quaterniond(home.linear())}};
  for (const BoxWaypoint& waypoint : plan.waypoints) {
    poses.push_back({waypoint.t_s, hand_position(plan, waypoint, side), facing, hand_force(waypoint, side)});
  }
  return poses;
}

/// The pose at t_s on the straight, minimum-jerk segments between the waypoints (the force
/// changes by the same law).
Pose pose_at(const std::vector<Pose>& poses, double t_s) {
  size_t i = 1;
  while (i + 1 < poses.size() && t_s > poses[i].t_s) ++i;
  const Pose& a = poses[i - 1];
  const Pose& b = poses[i];
  const double s = minimum_jerk(std::clamp((t_s - a.t_s) / (b.t_s - a.t_s), 0.0, 1.0));
  return {t_s, a.position_m + s * (b.position_m - a.position_m), a.rotation.slerp(s, b.rotation),
          a.force_n + s * (b.force_n - a.force_n)};
}

HandTrajectory plan_hand(const BoxPlan& plan, Side side, const IkSettings& settings) {
  sim::MujocoModel arm = sim::MujocoModel::load(plan.model(side));
  arm.reset(plan.home_keyframe);
  JointVector q = Eigen::Map<const JointVector>(arm.data()->qpos);
  HandIk ik(arm.model(), std::string(side_name(side)) + "_ee_site", q, settings);
  const std::vector<Pose> poses = flange_waypoints(plan, side, ik.flange_pose(q));

  HandTrajectory trajectory;
  trajectory.side = side;
  trajectory.min_limit_distance_rad = ik.limit_distance(q);
  const auto rows = static_cast<size_t>(std::lround(plan.duration_s() * plan.rate_hz)) + 1;
  for (size_t k = 0; k < rows; ++k) {
    const double t_s = static_cast<double>(k) / plan.rate_hz;
    const Pose target = pose_at(poses, t_s);
    const IkError error = ik.solve(target.position_m, target.rotation.toRotationMatrix(), q);
    trajectory.worst.position_m = std::max(trajectory.worst.position_m, error.position_m);
    trajectory.worst.rotation_rad = std::max(trajectory.worst.rotation_rad, error.rotation_rad);
    trajectory.min_limit_distance_rad = std::min(trajectory.min_limit_distance_rad, ik.limit_distance(q));
    trajectory.t_s.push_back(t_s);
    trajectory.q_rad.push_back(q);
    if (plan.has_force()) trajectory.tau_nm.push_back(ik.joint_torque(q, target.force_n));
  }
  return trajectory;
}

}  // namespace

std::array<HandTrajectory, 2> plan_hand_trajectories(const BoxPlan& plan, const IkSettings& settings) {
  return {plan_hand(plan, Side::kLeft, settings), plan_hand(plan, Side::kRight, settings)};
}

void write_trajectory_csv(const HandTrajectory& trajectory, const std::string& path) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot be written");
  out << "t_s";
  for (int j = 0; j < control::kDof; ++j) out << ",q_" << j;
  const bool torques = !trajectory.tau_nm.empty();
  if (torques) {
    for (int j = 0; j < control::kDof; ++j) out << ",tau_op_" << j;
  }
  out << '\n';
  char cell[32];
  for (size_t k = 0; k < trajectory.t_s.size(); ++k) {
    std::snprintf(cell, sizeof cell, "%.6f", trajectory.t_s[k]);
    out << cell;
    for (int j = 0; j < control::kDof; ++j) {
      std::snprintf(cell, sizeof cell, ",%.12f", trajectory.q_rad[k][j]);
      out << cell;
    }
    for (int j = 0; torques && j < control::kDof; ++j) {
      std::snprintf(cell, sizeof cell, ",%.9f", trajectory.tau_nm[k][j]);
      out << cell;
    }
    out << '\n';
  }
  if (!out) throw std::runtime_error(path + ": write failed");
}

}  // namespace teleop::box_task
