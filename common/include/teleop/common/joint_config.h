#pragma once
// Reading per-joint lists and 3-vectors from configuration.

#include <array>
#include <cmath>
#include <string>

#include "teleop/common/config.h"
#include "teleop/common/joint_model.h"

namespace teleop {

/// Joint angles in configuration [rad]: at most one turn either way.
inline constexpr Range kJointAngleRange{-2 * M_PI, 2 * M_PI};

/// Reads `key` as a list of exactly `joints` numbers within `range`; every joint gets
/// `fallback` when the key is absent. Throws ConfigError naming the key otherwise.
JointVector read_joint_list(const ConfigNode& section, const std::string& key, size_t joints, Range range,
                            double fallback);

/// Reads `key` as exactly 3 numbers (x, y, z) within `range`. Throws ConfigError naming the key.
std::array<double, 3> read_vector3(const ConfigNode& section, const std::string& key, Range range);
/// The same with `fallback` when the key is absent.
std::array<double, 3> read_vector3(const ConfigNode& section, const std::string& key, Range range,
                                   const std::array<double, 3>& fallback);

/// Reads the number-of-joints key `joints` (1..kMaxJoints).
size_t read_joint_count(const ConfigNode& section);

/// Reads the `model:` part every simulated joint space has (inertia, friction, wall).
JointModelParams read_joint_model(const ConfigNode& section, size_t joints);

}  // namespace teleop
