#pragma once
// Writing one swept parameter's value into a loaded MuJoCo model (parameter_sweep_config.h names
// the kinds): shared by the press sweep and the wiping study.

#include "parameter_sweep_config.h"
#include "teleop/sim/mujoco_model.h"

namespace teleop::experiment {

/// Whether `set` changes the model (every kind but the press scenario's press_depth_m).
bool is_model_parameter(const std::string& set);

/// Writes `value` into the model: a geom's or body's position along one axis, a geom's sliding
/// friction, or a body's orientation in its parent as a rotation of `value` rad about the
/// parent's x axis (the tool's mounting angle). The next mj_forward / step sees it. Throws
/// std::out_of_range naming a geom or body the model lacks, std::invalid_argument for a kind
/// that is not the model's.
void apply_model_parameter(const SweepParameter& p, double value, sim::MujocoModel& sim);

}  // namespace teleop::experiment
