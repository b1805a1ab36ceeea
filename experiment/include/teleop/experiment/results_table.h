#pragma once
// The experiment's rows as a table for the terminal and as CSV.

#include <string>
#include <vector>

#include "teleop/experiment/experiment_runner.h"

namespace teleop::experiment {

/// One line per row, aligned columns (the metrics of `kind`); "-" for a metric without samples;
/// the reasons for "unstable" and the errors listed below the table.
std::string format_table(const std::vector<RunRow>& rows, const std::string& title, AnalysedTask kind);

/// Header and one line per row (the metrics of `kind`); empty cells for metrics without samples.
std::string format_csv(const std::vector<RunRow>& rows, AnalysedTask kind);

/// The repeats of each run x profile summed up, one line each in the order of first appearance:
/// how many were ok and stable, and each metric's mean ± sample standard deviation over the ok
/// repeats that have it (a flag: how many of them said yes).
std::string format_summary_table(const std::vector<RunRow>& rows, AnalysedTask kind);

/// The same as CSV: run, profile, repeats, ok, stable, then <metric>_mean and <metric>_sd (empty
/// with fewer than two values) for every metric.
std::string format_summary_csv(const std::vector<RunRow>& rows, AnalysedTask kind);

/// Where the summary of the results CSV `csv_path` goes: <stem>_summary.csv beside it.
std::string summary_csv_path(const std::string& csv_path);

}  // namespace teleop::experiment
