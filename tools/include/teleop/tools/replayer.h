#pragma once
// `teleop replay DIR`: publishes a recording's samples again with their recorded timing (scaled
// by --rate), optionally only some topics, optionally in a loop. Headers are restamped with the
// replay's clocks (the receivers' staleness checks would refuse hour-old stamps); sequence
// numbers stay as recorded. With a compare topic, the live samples of that topic during the
// replay are compared with the recorded ones at the same point of the recording: record a run,
// replay the leader's commands to a fresh follower, and see how closely it moves the same way.

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "teleop/tools/topic_tools.h"

namespace teleop::tools {

struct ReplayOptions {
  std::string dir;
  /// Only these topics; empty: all of the recording.
  std::vector<std::string> topics;
  /// Speed: 2 plays twice as fast.
  double rate = 1.0;
  bool loop = false;
  /// Keep the recorded stamps instead of restamping.
  bool keep_stamps = false;
  /// Wait this long for every replayed topic to have a reader before starting [s].
  double wait_for_readers_s = 5.0;
  /// A recorded JointState topic to compare with its live samples during the replay; empty: none.
  std::string compare_topic;
};

struct ReplayResult {
  uint64_t published = 0;
  /// Publication time minus scheduled time [s].
  double timing_error_p50_s = 0.0;
  double timing_error_p99_s = 0.0;
  double timing_error_max_s = 0.0;
  /// Interval between consecutive publications minus the recorded interval, absolute [s].
  double interval_error_p50_s = 0.0;
  double interval_error_p99_s = 0.0;
  /// The comparison (compare_topic): live samples compared, RMSE and largest error over joints.
  uint64_t compared = 0;
  double rmse = 0.0;
  double max_error = 0.0;
};

/// Throws bag::BagError (a bad recording), std::runtime_error (an unknown topic or type).
ReplayResult replay(const BusOptions& bus, const ReplayOptions& options, FILE* log);

/// The summary lines of a replay.
std::string format_replay(const ReplayResult& result, const ReplayOptions& options);

}  // namespace teleop::tools
