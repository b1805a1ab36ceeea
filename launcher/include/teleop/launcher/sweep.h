#pragma once
// Runs one scenario under several network profiles, one after the other, and writes what each
// run measured into one CSV (a row per topic flow and profile).

#include <string>
#include <vector>

#include "teleop/launcher/launcher.h"

namespace teleop::launcher {

struct SweepResult {
  int failed_runs = 0;
  std::vector<std::string> report_dirs;
};

/// Launches `scenario` once per profile (with `base` options, its network replaced), and writes
/// `csv_path`. Throws std::runtime_error when the CSV cannot be written.
SweepResult sweep(const Scenario& scenario, const LaunchOptions& base, const std::vector<std::string>& profiles,
                  const std::string& csv_path);

/// The CSV rows of one run (header row first when `header`), for a profile name.
std::string csv_rows(const RunSummary& summary, const std::string& profile, bool header);

}  // namespace teleop::launcher
