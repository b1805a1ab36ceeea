#include "teleop/experiment/experiment_runner.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "teleop/common/config.h"
#include "box_task_analysis.h"
#include "report_files.h"
#include "teleop/experiment/plots.h"
#include "teleop/experiment/results_table.h"
#include "teleop/launcher/launcher.h"
#include "teleop/runtime/shutdown_signal.h"
#include "teleop/transport/impairment/impairment_config.h"

namespace teleop::experiment {
namespace fs = std::filesystem;
namespace {

constexpr int kDefaultFirstDomain = 60;
constexpr int kMaxDomain = 232;

struct SelectedRun {
  const RunSpec* spec;
  launcher::Scenario scenario;
};

std::string join(const std::vector<std::string>& items) {
  std::string out;
  for (const auto& i : items) out += (out.empty() ? "" : ", ") + i;
  return out;
}

// the file's runs, or those named by --runs, with their scenarios
std::vector<SelectedRun> select_runs(const ExperimentConfig& config, const std::vector<std::string>& names) {
  std::vector<std::string> known;
  for (const auto& r : config.runs) known.push_back(r.name);
  std::vector<SelectedRun> out;
  for (const auto& r : config.runs) {
    if (names.empty() || std::find(names.begin(), names.end(), r.name) != names.end()) {
      out.push_back({&r, launcher::load_scenario(r.scenario)});
    }
  }
  for (const auto& n : names) {
    if (std::find(known.begin(), known.end(), n) == known.end()) {
      throw ConfigError("--runs: " + config.file + " has no run '" + n + "' (runs: " + join(known) + ")");
    }
  }
  return out;
}

// every node must find every profile (it resolves the name next to its own config) and the
// scenario must hold the two nodes the analysis compares; checked before the first run
void check_runs(const ExperimentConfig& config, const std::vector<SelectedRun>& runs,
                const std::vector<std::string>& profiles) {
  for (const auto& run : runs) {
    for (const std::string& node : {config.analysis.leader, config.analysis.follower}) {
      const auto& nodes = run.scenario.nodes;
      if (std::none_of(nodes.begin(), nodes.end(), [&](const auto& n) { return n.name == node; })) {
        throw ConfigError(config.file + ": experiment.analysis: scenario " + run.scenario.file + " (run " +
                          run.spec->name + ") has no node '" + node + "'");
      }
    }
    for (const auto& profile : profiles) {
      if (profile == "none") continue;
      for (const auto& node : run.scenario.nodes) {
        if (transport::impairment::resolve_profile_path(profile, node.config).empty()) {
          throw ConfigError(config.file + ": experiment.profiles: no network profile '" + profile + "' for node " +
                            node.name + " of run " + run.spec->name + " (a file, or a name in config/network)");
        }
      }
    }
  }
}

// a profile given as a file gets the folder of its name without the directories
std::string profile_folder(const std::string& profile) {
  return profile.find('/') == std::string::npos ? profile : fs::path(profile).stem().string();
}

// the figures beside the CSV and in each run's folder; one that cannot be drawn is a warning: the
// numbers are the experiment's result, not its figures
// with the operator's start and the hold window on each run's, the verdict's limits on the metrics'
void write_figures(const ExperimentResult& result, const AnalysisConfig& analysis) {
  const auto warn = [](const PlotError& e) { std::printf("[experiment] warning: no figures: %s\n", e.what()); };
  try {
    const PlotTool tool = find_plot_tool();
    const RunMarks marks{analysis.leader, {{"hold", {analysis.hold.begin_s, analysis.hold.end_s}}}};
    for (const RunRow& row : result.rows) {
      try {
        plot_run(tool, row.trace_dir, row.trace_dir, marks);
      } catch (const PlotError& e) {
        warn(e);
      }
    }
    plot_results(tool, result.csv_path,
                 {{"mad_rad", analysis.stable_max_mad_rad},
                  {"force_mad_n", analysis.stable_max_force_mad_n},
                  {"saturation_fraction", analysis.stable_max_saturation},
                  {"safe_hold_fraction", analysis.stable_max_safe_hold},
                  {"flows_matched_s", flows_matched_limit_s(analysis)}});
  } catch (const PlotError& e) {
    warn(e);
  }
}

}  // namespace

RunRow analyse_run(const std::string& run, const std::string& profile, const std::string& trace_dir, bool launched_ok,
                   const AnalysisConfig& analysis) {
  RunRow row;
  row.run = run;
  row.profile = profile;
  row.status = launched_ok ? "ok" : "failed";
  row.trace_dir = trace_dir;
  try {
    const Trace leader = read_trace((fs::path(trace_dir) / (analysis.leader + ".csv")).string());
    const Trace follower = read_trace((fs::path(trace_dir) / (analysis.follower + ".csv")).string());
    if (analysis.kind == AnalysedTask::kBoxTask) {
      row.metrics = analyse_arms(leader, follower, analysis);
      row.box_task = box_task::evaluate_box_task(box_task_series(follower), analysis.shelf);
    } else {
      row.metrics = analyse(leader, follower, analysis);
    }
    row.verdict = judge_stability(row.metrics, analysis);
    if (const std::string invalid = invalid_reason(row.metrics, analysis); launched_ok && !invalid.empty()) {
      row.status = "invalid";
      row.note = invalid;
    }
  } catch (const TraceError& e) {
    if (launched_ok) row.status = "error";
    row.note = e.what();
  }
  // the failure explains a missing trace, not the other way round
  if (!launched_ok) row.note = "a node failed to start, run or stop cleanly (see its log above)";
  return row;
}

ExperimentResult run_experiment(const ExperimentConfig& config, const ExperimentOptions& options) {
  const std::vector<std::string> profiles = options.profiles.empty() ? config.profiles : options.profiles;
  const std::vector<SelectedRun> runs = select_runs(config, options.runs);
  check_runs(config, runs, profiles);

  ExperimentResult result;
  result.report_dir = make_report_dir(options.report_dir, "teleop-experiment-" + config.name + "-");
  result.csv_path =
      options.csv_path.empty() ? (fs::path(result.report_dir) / (config.name + ".csv")).string() : options.csv_path;
  const double duration_s = options.duration_s.value_or(config.duration_s);
  result.repeats = std::max(1, options.repeat);
  int domain = options.domain_id.value_or(kDefaultFirstDomain);
  const size_t total = runs.size() * profiles.size() * static_cast<size_t>(result.repeats);
  for (const auto& run : runs) {
    for (const auto& profile : profiles) {
      for (int repeat = 1; repeat <= result.repeats; ++repeat) {
        if (runtime::shutdown_requested()) break;
        launcher::LaunchOptions launch;
        launch.duration_s = duration_s;
        launch.domain_id = domain;
        domain = domain >= kMaxDomain ? 0 : domain + 1;
        launch.network = profile == "none" ? "" : profile;
        // each repeat its own loss pattern; every run of one repeat the same
        const uint64_t seed = config.seed + static_cast<uint64_t>(repeat - 1);
        launch.seed = seed;
        fs::path folder = fs::path(result.report_dir) / run.spec->name / profile_folder(profile);
        if (result.repeats > 1) folder /= "r" + std::to_string(repeat);
        launch.report_dir = folder.string();
        launch.trace_dir = launch.report_dir;
        // the whole run and then some: the ring never drops the start the analysis aligns on
        launch.trace_seconds = duration_s + run.scenario.stop_timeout_s + 5.0;
        launch.bin_dir = options.bin_dir;
        launch.sets = run.spec->sets;
        std::printf("\n[experiment] === %s: run %s, profile %s, repeat %d of %d (%zu of %zu, domain %d, seed %llu) ===\n",
                    config.name.c_str(), run.spec->name.c_str(), profile.c_str(), repeat, result.repeats,
                    result.rows.size() + 1, total, *launch.domain_id, static_cast<unsigned long long>(seed));
        std::fflush(stdout);
        const launcher::LaunchResult launched = launcher::launch(run.scenario, launch);
        std::printf("%s", launcher::format_summary(launched.summary, run.spec->name + " / " + profile).c_str());
        RunRow row = analyse_run(run.spec->name, profile, launch.trace_dir, launched.exit_code == 0, config.analysis);
        row.repeat = repeat;
        row.seed = seed;
        result.rows.push_back(std::move(row));
      }
    }
  }
  for (const auto& row : result.rows) result.failures += row.status == "ok" ? 0 : 1;
  if (result.rows.size() < total) {
    std::printf("[experiment] interrupted after %zu of %zu runs\n", result.rows.size(), total);
    result.failures += static_cast<int>(total - result.rows.size());
  }
  write_text(result.csv_path, format_csv(result.rows, config.analysis.kind));
  if (result.repeats > 1) write_text(summary_csv_path(result.csv_path), format_summary_csv(result.rows, config.analysis.kind));
  if (options.plots && !runtime::shutdown_requested()) write_figures(result, config.analysis);
  return result;
}

}  // namespace teleop::experiment
