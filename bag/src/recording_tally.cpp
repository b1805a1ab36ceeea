#include "recording_tally.h"

#include <algorithm>

namespace teleop::bag {

void RecordingTally::add_topic() {
  now_.topic_counts.push_back(0);
  committed_.topic_counts.push_back(0);
}

void RecordingTally::add(int topic_id, int64_t recv_ns, size_t bytes) {
  BagStats& s = now_.stats;
  s.first_ns = s.messages == 0 ? recv_ns : std::min(s.first_ns, recv_ns);
  s.last_ns = s.messages == 0 ? recv_ns : std::max(s.last_ns, recv_ns);
  ++s.messages;
  s.bytes += bytes;
  ++now_.topic_counts[static_cast<size_t>(topic_id - 1)];
}

void RecordingTally::commit() {
  ++now_.stats.commits;
  committed_ = now_;  // the topics' vector keeps its capacity: no allocation per commit
}

void RecordingTally::roll_back() { now_ = committed_; }

}  // namespace teleop::bag
