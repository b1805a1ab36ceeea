#pragma once
// The soak: a scenario's nodes run under a hostile network while, one at a time and at random
// (seeded), a node is killed with SIGKILL and started again. Each event is measured from the
// traces of the nodes that must react: how long until they hold (the safe state), how long from
// the new process's first cycle until they run again; over the whole soak, every cycle of the
// follower is checked for a stale command applied, a torque beyond its limit and a reflex
// threshold crossed without the reflex latching (docs/reliability.md).

#include <cmath>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace teleop::experiment {

struct SoakConfig {
  std::string name;
  std::string file;
  /// The scenario whose nodes are soaked (its sites decide which links the network impairs).
  std::string scenario_path;
  /// Network profile (name in config/network or a file) of the links between sites.
  std::string network;
  uint64_t seed = 1;
  /// Kills of each node; the nodes take turns in a seeded random order.
  int kills_per_node = 5;
  /// A node runs for a uniform random time in [up_min, up_max] before it is killed, and is
  /// started again after one in [down_min, down_max] [s]. Before the first kill all settle.
  double up_min_s = 2.0;
  double up_max_s = 4.0;
  double down_min_s = 0.2;
  double down_max_s = 1.0;
  double settle_s = 3.0;
  /// After the last restart, how long the soak goes on for the recovery to show [s].
  double end_s = 8.0;
  /// A resume not seen within this long of the new process's first cycle (DDS discovery over the
  /// lossy link included) is a failure; one cut short by the soak's end before that is pending.
  double resume_timeout_s = 30.0;
  /// node -> the nodes that must hold while it is gone and run again once it is back
  std::map<std::string, std::vector<std::string>> watch;
  /// The node whose every cycle is checked for stale commands, torque and reflex violations.
  std::string robot = "follower";
};

/// Reads a soak file (`soak:` section). Throws ConfigError naming file and key.
SoakConfig load_soak(const std::string& path);

struct SoakOptions {
  std::optional<int> kills_per_node;
  std::optional<uint64_t> seed;
  std::optional<int> domain_id;
  std::string report_dir;
  std::string bin_dir;
};

/// One kill and restart, times on CLOCK_MONOTONIC [s].
struct SoakEvent {
  std::string node;
  int incarnation = 0;  ///< of the process killed (0: the first)
  double killed_s = 0.0;
  double restarted_s = 0.0;
  /// The new process's first loop cycle (from its trace).
  double first_cycle_s = NAN;
  /// Until every watcher held (or was still starting: it holds then too), from the kill; until
  /// every watcher ran again, from the new process's first cycle (DDS discovery included). NaN:
  /// never while the watcher lived.
  double to_safe_s = NAN;
  double to_resume_s = NAN;
  /// Not resumed, and not for want of the system: a watcher was killed itself before it ran
  /// again (interrupted), or the soak ended sooner than resume_timeout_s after the first cycle
  /// (pending).
  bool interrupted = false;
  bool pending = false;
  /// Never held, or not resumed within the timeout: a failure.
  bool unrecovered() const { return std::isnan(to_safe_s) || (std::isnan(to_resume_s) && !interrupted && !pending); }
};

struct SoakResult {
  std::vector<SoakEvent> events;
  /// Over every cycle of every process of the robot node.
  uint64_t robot_cycles = 0;
  uint64_t stale_commands = 0;
  uint64_t torque_violations = 0;
  uint64_t reflex_violations = 0;
  uint64_t reflex_trips = 0;
  /// Processes that did not start, or traces that could not be read.
  int failures = 0;
  std::string report_dir;
  std::string csv_path;
};

/// Runs the soak (minutes), then analyses it. Throws ConfigError for a bad scenario.
SoakResult run_soak(const SoakConfig& config, const SoakOptions& options);

/// The table of a result: per node killed, events, time to safe state and to resume (p50, max),
/// and the violation counts.
std::string format_soak(const SoakResult& result, const std::string& name);

}  // namespace teleop::experiment
