#include "limits_in_force.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace teleop::follower {
namespace {

std::string joint_name(size_t i) { return "joint " + std::to_string(i + 1); }

}  // namespace

JointLimits limits_in_force(const JointLimits& configured, const robot::HardwareLimits& robot, size_t joints,
                            const std::string& robot_name) {
  JointLimits l = configured;
  for (size_t i = 0; i < joints; ++i) {
    l.q_min_rad[i] = std::max(configured.q_min_rad[i], robot.q_min_rad[i]);
    l.q_max_rad[i] = std::min(configured.q_max_rad[i], robot.q_max_rad[i]);
    l.max_torque_nm[i] = std::min(configured.max_torque_nm[i], robot.max_torque_nm[i]);
    if (!std::isfinite(l.q_min_rad[i]) || !std::isfinite(l.q_max_rad[i])) {
      throw std::runtime_error(joint_name(i) + " has no position limit: neither follower.q_min_rad/q_max_rad nor the robot (" +
                               robot_name + ") gives one");
    }
    if (!std::isfinite(l.max_torque_nm[i])) {
      throw std::runtime_error(joint_name(i) + " has no torque limit: neither follower.max_torque_nm nor the robot (" +
                               robot_name + ") gives one");
    }
    if (l.q_min_rad[i] >= l.q_max_rad[i]) {
      throw std::runtime_error(joint_name(i) + ": follower.q_min_rad/q_max_rad [" + std::to_string(configured.q_min_rad[i]) +
                               ", " + std::to_string(configured.q_max_rad[i]) + "] lies outside the robot's range [" +
                               std::to_string(robot.q_min_rad[i]) + ", " + std::to_string(robot.q_max_rad[i]) + "] (" +
                               robot_name + ")");
    }
  }
  return l;
}

std::string limits_text(const JointLimits& in_force, const JointLimits& configured, size_t joints) {
  std::string text;
  for (size_t i = 0; i < joints; ++i) {
    const bool range_typed = in_force.q_min_rad[i] == configured.q_min_rad[i] || in_force.q_max_rad[i] == configured.q_max_rad[i];
    const bool torque_typed = in_force.max_torque_nm[i] == configured.max_torque_nm[i];
    char joint[160];
    std::snprintf(joint, sizeof(joint), "%s%zu: [%.4f, %.4f] rad (%s), %.1f Nm (%s)", i == 0 ? "" : "; ", i + 1,
                  in_force.q_min_rad[i], in_force.q_max_rad[i], range_typed ? "config" : "robot", in_force.max_torque_nm[i],
                  torque_typed ? "config" : "robot");
    text += joint;
  }
  return text;
}

}  // namespace teleop::follower
