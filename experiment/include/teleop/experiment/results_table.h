#pragma once
// The experiment's rows as a table for the terminal and as CSV.

#include <string>
#include <vector>

#include "teleop/experiment/experiment_runner.h"

namespace teleop::experiment {

/// One line per row, aligned columns; "-" for a metric without samples; the reasons for
/// "unstable" and the errors listed below the table.
std::string format_table(const std::vector<RunRow>& rows, const std::string& title);

/// Header and one line per row; empty cells for metrics without samples.
std::string format_csv(const std::vector<RunRow>& rows);

}  // namespace teleop::experiment
