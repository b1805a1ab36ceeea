#include "wiping_trajectory.h"

#include <algorithm>
#include <cmath>

#include "teleop/control/min_jerk.h"

namespace teleop::experiment {
namespace {

// the tool over the panel: blade (x) up the slope, face (z) into the surface, then tilted by the
// lean about the blade
Eigen::Matrix3d planned_tool_rotation(const PanelFrame& panel, double lean_rad) {
  Eigen::Matrix3d flat;
  flat.col(0) = panel.v;
  flat.col(2) = -panel.n;
  flat.col(1) = flat.col(2).cross(flat.col(0));
  return flat * Eigen::AngleAxisd(lean_rad, Eigen::Vector3d::UnitX()).toRotationMatrix();
}

}  // namespace

WipingTrajectory::WipingTrajectory(const WipingPlan& plan, const PanelFrame& panel,
                                   const Eigen::Isometry3d& tool_in_hand, const Eigen::Isometry3d& hand_start) {
  tool_rotation_ = planned_tool_rotation(panel, plan.tool_lean_rad);
  const Eigen::Matrix3d hand_rotation = tool_rotation_ * tool_in_hand.linear().transpose();
  const Eigen::Quaterniond q_hand(hand_rotation);
  // the hand where the tool site is at `tool`
  const auto hand_at = [&](const Eigen::Vector3d& tool) {
    return Eigen::Vector3d(tool - hand_rotation * tool_in_hand.translation());
  };
  const auto tool_point = [&](double u, double v, double n) {
    return Eigen::Vector3d(panel.centre + u * panel.u + v * panel.v + n * panel.n);
  };

  segments_.push_back({0.0, 0.0, hand_start.translation(), hand_start.translation(),
                       Eigen::Quaterniond(hand_start.linear()), Eigen::Quaterniond(hand_start.linear())});
  const size_t wipes = plan.press_depth_m.size();
  const double half = 0.5 * plan.stroke_length_m;
  for (size_t i = 0; i < wipes; ++i) {
    // back and forth: the even wipes go along +u, the odd ones back
    const double u_from = (i % 2 == 0) ? -half : half;
    const double v = (static_cast<double>(i) - 0.5 * static_cast<double>(wipes - 1)) * plan.stroke_spacing_m;
    const double depth = plan.press_depth_m[i];
    add(i == 0 ? plan.reach_s : plan.shift_s, hand_at(tool_point(u_from, v, plan.hover_m)), q_hand);
    const double begin = duration_s();
    add(plan.press_s, hand_at(tool_point(u_from, v, -depth)), q_hand);
    add(plan.stroke_s, hand_at(tool_point(-u_from, v, -depth)), q_hand);
    add(plan.lift_s, hand_at(tool_point(-u_from, v, plan.hover_m)), q_hand);
    windows_.emplace_back(begin, duration_s());
  }
  add(plan.settle_s, segments_.back().to, q_hand);
}

void WipingTrajectory::add(double length_s, const Eigen::Vector3d& to, const Eigen::Quaterniond& q_to) {
  const Segment& last = segments_.back();
  segments_.push_back({last.t0_s + last.length_s, length_s, last.to, to, last.q_to, q_to});
}

HandSetPoint WipingTrajectory::at(double t_s) const {
  // the segment holding t (the last one after the end)
  auto it = std::upper_bound(segments_.begin(), segments_.end(), t_s,
                             [](double t, const Segment& s) { return t < s.t0_s + s.length_s; });
  if (it == segments_.end()) --it;
  const Segment& s = *it;
  const double tau = s.length_s > 0.0 ? std::clamp((t_s - s.t0_s) / s.length_s, 0.0, 1.0) : 1.0;
  const double rate = s.length_s > 0.0 && t_s <= s.t0_s + s.length_s ? control::min_jerk_rate(tau) / s.length_s : 0.0;
  HandSetPoint p;
  p.position = s.from + control::min_jerk_progress(tau) * (s.to - s.from);
  p.orientation = s.q_from.slerp(control::min_jerk_progress(tau), s.q_to);
  p.twist.head<3>() = rate * (s.to - s.from);
  // the slerp's angular rate: the rotation from start to goal, about its axis
  const Eigen::AngleAxisd turn(s.q_to * s.q_from.inverse());
  p.twist.tail<3>() = rate * turn.angle() * turn.axis();
  return p;
}

}  // namespace teleop::experiment
