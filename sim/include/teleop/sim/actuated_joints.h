#pragma once
// The joints a controller drives in a MuJoCo model: hinge joints with a joint-transmission
// actuator, in actuator order (the order of the command and state samples).

#include <mujoco/mujoco.h>

#include <array>
#include <cstddef>
#include <string>

namespace teleop::sim {

inline constexpr size_t kMaxActuatedJoints = 32;

struct ActuatedJoints {
  size_t count = 0;
  std::array<int, kMaxActuatedJoints> qpos{};      ///< index in qpos
  std::array<int, kMaxActuatedJoints> dof{};       ///< index in qvel / qfrc_*
  std::array<int, kMaxActuatedJoints> actuator{};  ///< index in ctrl
};

/// Finds them; with a `name_prefix` only the joints whose names start with it (one arm of a
/// multi-arm model: "left_"). Throws std::runtime_error naming `model_name` when there are none
/// or too many.
ActuatedJoints find_actuated_joints(const mjModel* m, const std::string& model_name, const std::string& name_prefix = "");

}  // namespace teleop::sim
