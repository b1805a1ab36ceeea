#pragma once
// Runs the cells of a sweep in `jobs` worker processes (fork: the cells share nothing, and a
// crashing cell takes only its worker down) and collects one line of text per cell. Shared by
// the press sweep (parameter_sweep.h) and the wiping study (wiping_study.h).

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace teleop::experiment {

/// Calls `run_cell(i)` for every i < cells, cell i in worker i % jobs, and returns the lines in
/// cell order; a cell whose worker died is an empty string (newlines in a cell's text become
/// spaces). Allocates, forks; throws std::invalid_argument for jobs < 1, std::runtime_error when
/// its folder or a worker cannot be made.
std::vector<std::string> run_in_workers(size_t cells, int jobs, const std::function<std::string(size_t)>& run_cell);

}  // namespace teleop::experiment
