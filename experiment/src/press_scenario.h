#pragma once
// One run of a sweep: the press scenario (sweep_config.h) on the twin's simulation with one point
// of the parameter grid applied, and what came out of it.

#include <string>
#include <vector>

#include "parameter_sweep_config.h"

namespace teleop::experiment {

struct VariantOutcome {
  std::vector<double> values;
  /// Steps with at least one contact in the first contact pair.
  int contact_steps = 0;
  /// Largest and mean (over the last quarter of the run) contact force of that pair [N].
  double peak_force_n = 0.0;
  double mean_force_n = 0.0;
  /// Distance of the tool site from its target at the end: what the surface held it back [m].
  double final_error_m = 0.0;
  double wall_time_s = 0.0;
  /// Simulated over wall time.
  double rt_factor = 0.0;
  int mujoco_warnings = 0;
  /// Empty when the run worked; what went wrong otherwise.
  std::string error;
};

/// Runs one variant. Never throws: a failure is reported in `error`.
VariantOutcome run_press_variant(const SweepConfig& config, const std::vector<double>& values);

}  // namespace teleop::experiment
