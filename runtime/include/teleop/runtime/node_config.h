#pragma once
// The `node:` section every node config has.

#include <cstdint>
#include <string>
#include <vector>

#include "teleop/common/config.h"
#include "teleop/runtime/realtime.h"

namespace teleop::runtime {

struct NodeConfig {
  /// Node name: goes into every sample header and the logs.
  std::string name;
  /// Control loop rate [Hz].
  double rate_hz = 1000.0;
  /// NodeStatus publication rate [Hz].
  double status_rate_hz = 10.0;
  /// Run time [s]; 0 runs until SIGINT/SIGTERM.
  double duration_s = 0.0;
  /// Deadlines a late loop may still catch up on before it drops them (see RatePacer).
  uint64_t max_catch_up_cycles = 10;
  /// Locked memory and SCHED_FIFO for the loop thread.
  RealtimeConfig realtime;
  /// Observers an experiment adds to the node, by the names its executable registered them under
  /// (robot/scene_probes.h); empty: none.
  std::vector<std::string> probes;

  int64_t period_ns() const { return static_cast<int64_t>(1e9 / rate_hz); }
};

/// Reads the `node:` section. Throws ConfigError naming file and key.
NodeConfig parse_node_config(const ConfigNode& section, const std::string& default_name);

}  // namespace teleop::runtime
