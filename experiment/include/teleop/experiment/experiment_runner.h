#pragma once
// Runs every run x profile of an experiment through the launcher, one after the other, and
// analyses the traces they leave.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "teleop/experiment/analysis.h"
#include "teleop/experiment/experiment_config.h"

namespace teleop::experiment {

struct ExperimentOptions {
  /// Subsets/replacements of the file's lists; empty: all of the file's.
  std::vector<std::string> profiles;
  std::vector<std::string> runs;
  std::optional<double> duration_s;
  /// The CSV; empty: <report_dir>/<name>.csv.
  std::string csv_path;
  /// Traces and node reports go to <report_dir>/<run>/<profile>/; empty: a new folder in /tmp.
  std::string report_dir;
  std::string bin_dir;
  /// DDS domain of the first run; each further run takes the next one. Default 60.
  std::optional<int> domain_id;
  /// Figures (plots.h): one per metric beside the CSV, each run's in its folder. A figure that
  /// cannot be drawn is a warning, never the experiment's failure.
  bool plots = true;
  /// Each run x profile this many times, repeat k (from 1) with the impairment seed
  /// experiment.seed + k - 1, its traces in <run>/<profile>/r<k>/; the table then adds each
  /// cell's mean ± spread over its ok repeats and the figures error bars.
  int repeat = 1;
};

/// One table row: a run under a profile.
struct RunRow {
  std::string run;
  std::string profile;
  /// Which repeat of run x profile (from 1) and the impairment seed it ran with.
  int repeat = 1;
  uint64_t seed = 0;
  /// "ok"; "failed" (a node failed to start, run or stop cleanly); "error" (the traces could not
  /// be analysed; `note` says why); "invalid" (its flows matched late or never, so its numbers are
  /// no result: invalid_reason() in `note`).
  std::string status;
  std::string note;
  std::string trace_dir;
  RunMetrics metrics;
  Verdict verdict;
  /// The box task's own metrics (analysis.task: box_task), when the traces could be analysed.
  std::optional<box_task::BoxTaskMetrics> box_task;
};

struct ExperimentResult {
  std::vector<RunRow> rows;
  /// Repeats of each run x profile (ExperimentOptions::repeat).
  int repeats = 1;
  std::string report_dir;
  std::string csv_path;
  /// Rows whose status is not "ok".
  int failures = 0;
};

/// Runs the experiment and writes the CSV (and the figures, unless options.plots is false). Throws ConfigError for bad options (an unknown run,
/// a profile no node can find) before any run starts; std::runtime_error when the CSV cannot be
/// written.
ExperimentResult run_experiment(const ExperimentConfig& config, const ExperimentOptions& options);

/// The row of one finished run: analyses its traces in `trace_dir` (named <node>.csv).
RunRow analyse_run(const std::string& run, const std::string& profile, const std::string& trace_dir, bool launched_ok,
                   const AnalysisConfig& analysis);

}  // namespace teleop::experiment
