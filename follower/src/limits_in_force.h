#pragma once
// The joint limits a follower enforces: the robot's own (its model's joint ranges and motor
// limits, a drive's configured range), tightened by what the follower's config types. A config
// that types none takes the model's, so nothing is typed twice; a joint that ends with no finite
// limit, or with a configured range outside the robot's, stops the follower at start.

#include <cstddef>
#include <string>

#include "teleop/follower/command_validator.h"
#include "teleop/robot/robot_hardware.h"

namespace teleop::follower {

/// `configured` (infinite where the config is silent) intersected with `robot`. Throws
/// std::runtime_error naming the joint, the key and `robot_name` when a joint has no finite
/// position or torque limit or when the two ranges do not overlap.
JointLimits limits_in_force(const JointLimits& configured, const robot::HardwareLimits& robot, size_t joints,
                            const std::string& robot_name);

/// One line for the log: each joint's range and torque limit, and whose they are.
std::string limits_text(const JointLimits& in_force, const JointLimits& configured, size_t joints);

}  // namespace teleop::follower
