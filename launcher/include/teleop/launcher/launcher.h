#pragma once
// Runs a scenario: starts its nodes as separate processes, forwards their logs, stops them
// together and prints the summary.

#include <optional>
#include <string>
#include <vector>

#include "teleop/launcher/scenario.h"
#include "teleop/launcher/summary.h"

namespace teleop::launcher {

struct LaunchOptions {
  /// Overrides the scenario's duration [s].
  std::optional<double> duration_s;
  /// Overrides every node's DDS domain id (runs side by side without cross-talk).
  std::optional<int> domain_id;
  /// Impairs every node's outgoing traffic with this profile (name or file): both directions of
  /// every link. Empty: the node configs decide.
  std::string network;
  /// Seed of the impairment decisions, passed to every node.
  std::optional<uint64_t> seed;
  /// Where the nodes write their reports; a fresh temporary directory when empty.
  std::string report_dir;
  /// Directory holding the node executables; empty: next to this program, then PATH.
  std::string bin_dir;
  /// Config overrides "NODE:KEY=VALUE" for the node named NODE (after the scenario's `set:`).
  std::vector<std::string> sets;
  /// Where each node writes its time trace (`<trace_dir>/<node name>.csv`); empty: no traces.
  std::string trace_dir;
  /// Seconds of trace each node keeps (`--trace-seconds`); default: the node's own.
  std::optional<double> trace_seconds;
};

struct LaunchResult {
  /// 0 when every node started, ran and stopped cleanly and reported.
  int exit_code = 0;
  std::string report_dir;
  RunSummary summary;
};

/// The `--set KEY=VALUE` overrides of one node: the scenario's, then the options' "NODE:KEY=VALUE"
/// for it. Throws ConfigError for a malformed option or one naming no node of the scenario.
std::vector<std::string> node_overrides(const Scenario& scenario, const NodeLaunch& node,
                                        const std::vector<std::string>& sets);

/// The command line that starts `node` of `scenario` with `options` (domain, impairment of the
/// links to other sites, seed, overrides), writing its report to `report_path` and, unless empty,
/// its trace to `trace_path`.
std::vector<std::string> node_argv(const Scenario& scenario, const NodeLaunch& node, const LaunchOptions& options,
                                   const std::string& report_path, const std::string& trace_path);

/// Runs the scenario to the end (its duration, SIGINT/SIGTERM, or a node failing).
LaunchResult launch(const Scenario& scenario, const LaunchOptions& options);

/// Finds a node executable: a path as given, else in `bin_dir`, else next to this program,
/// else on PATH. Throws std::runtime_error naming it when not found.
std::string find_executable(const std::string& name, const std::string& bin_dir);

}  // namespace teleop::launcher
