#pragma once
// What a node measured during its run, written as YAML at exit for the launcher's summary.

#include <cstdint>
#include <string>
#include <vector>

#include "teleop/common/rate_pacer.h"
#include "teleop/transport/publication.h"
#include "teleop/transport/subscription.h"

namespace teleop::runtime {

struct PublishedTopic {
  std::string topic;
  uint64_t sent = 0;
  uint64_t failed = 0;
  /// How long a write took: nothing on the bus may make the loop's writes wait.
  int64_t write_p99_ns = 0;
  int64_t write_max_ns = 0;
};

struct ReceivedTopic {
  std::string topic;
  uint64_t received = 0;
  uint64_t expected = 0;  ///< last_seq - first_seq + 1, summed over the sessions
  uint64_t lost = 0;
  uint64_t duplicates = 0;
  uint64_t reordered = 0;
  uint64_t first_seq = 0;
  uint64_t last_seq = 0;
  double rate_hz = 0.0;
  int64_t latency_p50_ns = 0;
  int64_t latency_p99_ns = 0;
  int64_t latency_max_ns = 0;
  uint64_t deadline_missed = 0;
  uint64_t liveliness_lost = 0;
  /// Runs of samples missed in a row, as seen on arrival.
  uint64_t gap_max = 0;
  double gap_mean = 0.0;
  /// Age of the newest sample each time the loop looked (application-level effect).
  int64_t age_p50_ns = 0;
  int64_t age_p99_ns = 0;
  int64_t age_max_ns = 0;
  /// Writers followed in turn (a restarted peer opens a new session), and samples refused:
  /// another writer's while the followed one talked, or a sequence number that leapt.
  uint64_t sessions = 0;
  uint64_t refused_other_writer = 0;
  uint64_t refused_sequence_jump = 0;
  /// Samples of nodes the flow does not accept, and newest samples the node found invalid.
  uint64_t refused_not_accepted = 0;
  uint64_t refused_invalid = 0;
  /// The followed writer's clock against ours at the end, and its largest magnitude over the run
  /// (transport::Subscription::clock_offset_ns) [ns].
  int64_t clock_offset_ns = 0;
  int64_t clock_offset_max_ns = 0;
};

/// What the impairment did to one outgoing link of the node.
struct ImpairedLink {
  std::string to;
  std::string profile;
  uint64_t messages = 0;
  uint64_t delivered = 0;
  uint64_t lost = 0;
  uint64_t outage = 0;
  uint64_t queue = 0;
  uint64_t duplicated = 0;
  uint64_t reordered = 0;
  double loss_burst_mean = 0.0;
  uint64_t loss_burst_max = 0;
  int64_t delay_p50_ns = 0;
  int64_t delay_p99_ns = 0;
  int64_t delay_max_ns = 0;
  /// Configured (expected) loss rate and base delay of the profile's first phase.
  double configured_loss = 0.0;
  int64_t configured_delay_ns = 0;
};

struct NodeReport {
  std::string name;
  std::string role;
  std::string final_state;
  double rate_hz = 0.0;
  double run_time_s = 0.0;
  uint64_t cycles = 0;
  uint64_t overruns = 0;
  uint64_t skipped = 0;
  int64_t lateness_p50_ns = 0;
  int64_t lateness_p99_ns = 0;
  int64_t lateness_max_ns = 0;
  /// From SIGINT/SIGTERM to the participant being gone [ms]; negative when not signalled.
  double shutdown_ms = -1.0;
  std::vector<PublishedTopic> published;
  std::vector<ReceivedTopic> received;
  /// Impaired outgoing links (empty without impairment) and the seed of their decisions.
  std::vector<ImpairedLink> links;
  uint64_t impairment_seed = 0;
  /// Extra per-node figures (name, value), e.g. rejected commands.
  std::vector<std::pair<std::string, double>> counters;

  void add_loop(const PacerStats& stats);

  template <typename T>
  void add(const transport::Publication<T>& pub) {
    published.push_back({pub.topic_name(), pub.sent(), pub.failed(), pub.write_time().percentile_ns(0.99),
                         pub.write_time().max_ns()});
  }

  template <typename T>
  void add(const transport::Subscription<T>& sub) {
    received.push_back(received_from(sub.topic_name(), sub.stats(), sub.age(), sub.reader().deadline_missed(),
                                     sub.reader().liveliness_lost(), sub.session()));
    received.back().refused_not_accepted = sub.refused_not_accepted();
    received.back().refused_invalid = sub.rejected();
    received.back().clock_offset_ns = sub.clock_offset_ns();
    received.back().clock_offset_max_ns = sub.clock_offset_max_ns();
  }

  /// Adds the participant's impaired links.
  void add_links(const transport::Participant& participant);

  static ReceivedTopic received_from(const std::string& topic, const SequenceTracker& stats,
                                     const DurationHistogram& age, uint64_t deadline_missed, uint64_t liveliness_lost,
                                     const StreamSession& session = StreamSession{});
};

/// Writes the report as YAML. Throws std::runtime_error when the file cannot be written.
void write_report(const NodeReport& report, const std::string& path);
/// Reads a report written by write_report. Throws ConfigError on a malformed file.
NodeReport read_report(const std::string& path);

}  // namespace teleop::runtime
