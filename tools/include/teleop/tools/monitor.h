#pragma once
// `teleop monitor`: a live view of every node on the bus from its NodeStatus, refreshed once a
// second; one line per node per refresh when the output is not a terminal.

#include <cstdio>

#include "teleop/tools/topic_tools.h"

namespace teleop::tools {

struct MonitorOptions {
  double refresh_s = 1.0;
  /// Stop after this long (0: until interrupted).
  double duration_s = 0.0;
  /// Lines instead of a redrawn screen (default: when the output is not a terminal).
  bool lines = false;
};

int run_monitor(const BusOptions& bus, const MonitorOptions& options, FILE* out);

}  // namespace teleop::tools
