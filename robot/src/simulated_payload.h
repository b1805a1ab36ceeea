#pragma once
// The MJCF of a simulated payload (mujoco_scene.h's SimulatedPayload): a body with the tool's
// mass at its centre of mass, placed under the body that carries the site.

#include <mujoco/mujoco.h>

#include <string>

#include "teleop/robot/mujoco_scene.h"
#include "teleop/sim/model_additions.h"

namespace teleop::robot {

/// The body to add to `model` (loaded from `path`, named in errors). Throws std::runtime_error
/// when the model has no such site.
sim::ModelAddition payload_addition(const mjModel* model, const std::string& path, const SimulatedPayload& payload);

}  // namespace teleop::robot
