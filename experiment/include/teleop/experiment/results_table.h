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

}  // namespace teleop::experiment
