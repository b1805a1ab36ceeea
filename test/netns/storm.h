#pragma once
// The storm of issue 28 as a reusable run: a follower and its leader on one "host", readers of
// the follower's streams beside them, and on a second host participants that join the domain and
// leave it again, over and over (teleop_discovery_churn). Used by the storm test (flow and
// blocking) and by bench/storm_bench (lateness and holds, storm against quiet).

#include <string>

#include "teleop/runtime/node_report.h"

namespace teleop::test {

struct StormOptions {
  bool storm = true;       ///< false: the same run without readers and churn (the quiet baseline)
  int readers = 20;        ///< `teleop topic hz` readers of the follower's state and wrench
  int participants = 30;   ///< joining and leaving from the second host, each round
  double seconds = 15;     ///< how long the storm lasts
  std::string realtime = "off";  ///< the follower's and leader's node.realtime
};

struct StormResult {
  std::string error;  ///< what went wrong starting or stopping the run ("" when it ran)
  /// The storm's own processes (readers, churn) that Fast DDS 2.9 aborted in its participant
  /// removal race (docs/reliability.md): they stormed all the same; the follower and leader
  /// aborting would be an error.
  int storm_processes_aborted = 0;
  runtime::NodeReport follower;
  runtime::NodeReport leader;
  int churn_rounds = 0;       ///< rounds of joining and leaving the churn completed
  int participants_joined = 0;  ///< the churn's participants that were up (a starved round is partial)
  /// The churn's last run was still deleting its participants well after the storm and was killed.
  bool churn_killed_after_the_storm = false;
  int readers_reporting = 0;  ///< readers that printed a rate line (they received samples)
  std::string outputs;        ///< every process's output, for failure messages
};

/// Builds a two-host network (needs root: netns_unavailable_reason()), runs, stops, reads.
StormResult run_storm(const StormOptions& options);

/// The follower's figures in a few lines: holds, lateness, writes, command flow.
std::string describe(const StormResult& result);

}  // namespace teleop::test
