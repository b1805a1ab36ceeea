#pragma once
// An experiment file: several runs (architectures, each a scenario) under several network
// profiles, with the analysis settings that turn their traces into metrics.

#include <cstdint>
#include <string>
#include <vector>

#include "teleop/experiment/analysis.h"

namespace teleop::experiment {

/// One architecture: a name for the table and the scenario that runs it.
struct RunSpec {
  std::string name;
  std::string scenario;  ///< path, resolved relative to the experiment file
  /// Overrides for this run, `NODE:KEY=VALUE` as `teleop launch --set` (after the scenario's own).
  std::vector<std::string> sets;
};

struct ExperimentConfig {
  std::string name;
  std::string file;
  double duration_s = 10.0;  ///< each run
  uint64_t seed = 1;         ///< impairment seed, the same for every run
  /// Network profiles: names in config/network, files, or "none" (unimpaired).
  std::vector<std::string> profiles;
  std::vector<RunSpec> runs;
  AnalysisConfig analysis;
};

/// Reads an experiment file. Throws ConfigError naming the file, the key and the problem
/// (including a scenario file that is missing or itself invalid).
ExperimentConfig load_experiment(const std::string& path);

}  // namespace teleop::experiment
