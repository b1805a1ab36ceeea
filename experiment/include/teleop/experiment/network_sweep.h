#pragma once
// The network sweep: one scenario under several network profiles, one after the other, and what
// each run measured in one CSV (a row per topic flow and profile). (The parameter sweep varies a
// simulated world instead: parameter_sweep.h.)

#include <string>
#include <vector>

#include "teleop/launcher/launcher.h"

namespace teleop::experiment {

struct NetworkSweepResult {
  int failed_runs = 0;
  std::vector<std::string> report_dirs;
};

/// Launches `scenario` once per profile (with `base` options, its network replaced), and writes
/// `csv_path`. Throws std::runtime_error when the CSV cannot be written.
NetworkSweepResult network_sweep(const launcher::Scenario& scenario, const launcher::LaunchOptions& base, const std::vector<std::string>& profiles,
                  const std::string& csv_path);

/// The CSV rows of one run (header row first when `header`), for a profile name.
std::string csv_rows(const launcher::RunSummary& summary, const std::string& profile, bool header);

}  // namespace teleop::experiment
