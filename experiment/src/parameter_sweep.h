#pragma once
// Runs every variant of a sweep in `jobs` worker processes (sweep_workers.h) and collects their
// outcomes as a table.

#include <string>
#include <vector>

#include "press_scenario.h"
#include "parameter_sweep_config.h"

namespace teleop::experiment {

/// The table as CSV, a header and one row per variant in grid order: one column per parameter,
/// then the outcome columns (VariantOutcome's fields). A variant whose worker died is a row with
/// that error. Allocates, forks; throws std::runtime_error when no worker can be started.
std::string run_sweep(const SweepConfig& config);

/// The CSV row of one outcome (no newline).
std::string outcome_row(const VariantOutcome& outcome);

}  // namespace teleop::experiment
