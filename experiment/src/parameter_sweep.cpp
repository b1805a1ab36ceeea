#include "parameter_sweep.h"

#include <sstream>

#include "report_files.h"
#include "sweep_workers.h"

namespace teleop::experiment {
namespace {

constexpr const char* kOutcomeColumns =
    "contact_steps,peak_force_n,mean_force_n,final_error_m,wall_time_s,rt_factor,mujoco_warnings,error";

}  // namespace

std::string outcome_row(const VariantOutcome& o) {
  std::ostringstream r;
  r.precision(10);
  for (double v : o.values) r << v << ',';
  r << o.contact_steps << ',' << o.peak_force_n << ',' << o.mean_force_n << ',' << o.final_error_m << ','
    << o.wall_time_s << ',' << o.rt_factor << ',' << o.mujoco_warnings << ',' << csv_quoted(o.error);
  return r.str();
}

std::string run_sweep(const SweepConfig& config) {
  const auto grid = sweep_grid(config.parameters);
  std::vector<std::string> rows = run_in_workers(
      grid.size(), config.jobs, [&](size_t i) { return outcome_row(run_press_variant(config, grid[i])); });

  std::ostringstream csv;
  for (const SweepParameter& p : config.parameters) csv << p.name << ',';
  csv << kOutcomeColumns << '\n';
  for (size_t i = 0; i < grid.size(); ++i) {
    if (rows[i].empty()) {
      VariantOutcome died;
      died.values = grid[i];
      died.error = "the worker died";
      rows[i] = outcome_row(died);
    }
    csv << rows[i] << '\n';
  }
  return csv.str();
}

}  // namespace teleop::experiment
