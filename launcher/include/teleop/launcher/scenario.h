#pragma once
// A scenario: which nodes to start, with which configs, for how long.

#include <string>
#include <vector>

namespace teleop::launcher {

struct NodeLaunch {
  /// Unique name: prefixes its log lines and names its report file.
  std::string name;
  /// Executable name (looked up next to the launcher, then on PATH) or a path.
  std::string executable;
  /// Node config file, resolved relative to the scenario file.
  std::string config;
  /// Extra command-line arguments.
  std::vector<std::string> args;
  /// Config overrides "KEY=VALUE" from the entry's `set:` mapping, passed as `--set`.
  std::vector<std::string> sets;
  /// Where the node runs ("" = unspecified). When nodes name their sites, a network profile
  /// impairs only the links between different sites (the operator's leader and its local twin
  /// talk unimpaired, both reach the remote follower over the impaired link). The node's own
  /// name (node.name in its config) must equal `name` for that.
  std::string site;
};

struct Scenario {
  std::string name;
  std::string file;
  /// Run time [s]; 0 runs until SIGINT/SIGTERM.
  double duration_s = 5.0;
  /// Time the nodes get to stop after SIGTERM before they are killed [s].
  double stop_timeout_s = 5.0;
  std::vector<NodeLaunch> nodes;
};

/// Reads a scenario file. Throws ConfigError naming file, key and problem.
Scenario load_scenario(const std::string& path);

}  // namespace teleop::launcher
