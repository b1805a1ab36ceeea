#pragma once
// A parameter sweep over an uncertain world (thesis §4.4): one scenario, run once per point of a
// grid of parameter values, each run a simulation of the twin's kind (config/sweeps/*.yaml,
// docs/twin.md).

#include <string>
#include <vector>

#include "teleop/common/config.h"
#include "teleop/twin/twin_model_config.h"

namespace teleop::experiment {

/// The scenario: a Cartesian impedance (PARTI eq. 4) presses the tool site from where it starts
/// straight down towards a target `depth_m` below, reached linearly over `approach_time_s`; the
/// contact force is then set by how far the target lies behind the surface (thesis §4.4.1).
struct PressScenario {
  std::string site = "tool_site";
  double depth_m = 0.3;
  double approach_time_s = 0.8;
  double stiffness_n_per_m = 500.0;
};

/// One swept parameter: `set` names what it changes, `values` the grid points.
///   geom_pos_x|y|z:NAME, body_pos_x|y|z:NAME   position of a geom / body in its parent [m]
///   geom_friction:NAME                         sliding friction coefficient of a geom
///   body_angle_x:NAME                          orientation of a body in its parent: a rotation
///                                              about the parent's x axis [rad] (a tool's mounting angle)
///   press_depth_m                              the scenario's target depth [m]
struct SweepParameter {
  std::string name;
  std::string set;
  std::vector<double> values;
};

struct SweepConfig {
  twin::TwinModelConfig model;
  PressScenario press;
  double duration_s = 1.5;
  std::vector<SweepParameter> parameters;
  /// Worker processes.
  int jobs = 2;
};

/// Reads the `sweep:` section. Throws ConfigError naming file and key.
SweepConfig parse_sweep_config(const ConfigNode& root);

/// Reads one entry of a `parameters:` list ({name, set, values}). Throws ConfigError naming the key.
SweepParameter read_sweep_parameter(const ConfigNode& p);

/// The grid: every combination of the parameters' values, the first parameter varying slowest.
std::vector<std::vector<double>> sweep_grid(const std::vector<SweepParameter>& parameters);

}  // namespace teleop::experiment
