#pragma once
// A reader plus reception statistics: the loop calls `poll()` once per cycle to drain what
// arrived, and reads the newest sample with `latest()`.

#include <cstdint>
#include <string>
#include <utility>

#include "teleop/common/clock.h"
#include "teleop/common/sequence_tracker.h"
#include "teleop/transport/participant.h"

namespace teleop::transport {

template <typename T>
class Subscription {
 public:
  /// Setup time: creates the reader.
  Subscription(Participant& participant, const TopicSpec<T>& topic)
      : topic_name_(topic.name), reader_(participant.make_reader(topic)) {}

  /// Takes every sample that arrived since the last poll, updates the statistics and keeps
  /// the newest as `latest()`. Non-blocking and real-time safe. Returns the number taken.
  int poll() {
    int taken = 0;
    int64_t reception_ns = 0;
    while (reader_.take_next(incoming_, reception_ns)) {
      const auto& header = incoming_.header();
      // latency of the transport itself: source stamp to DDS reception, not to this poll
      tracker_.on_sample(header.seq(), header.stamp_ns(), reception_ns);
      if (!has_sample_ || header.seq() > latest_.header().seq()) {
        // swap, not copy: both buffers keep their capacity, nothing is allocated
        std::swap(latest_, incoming_);
        has_sample_ = true;
        latest_receive_mono_ns_ = monotonic_now_ns();
      }
      ++taken;
    }
    // what the loop works with: how old the newest sample is now
    if (has_sample_) age_.record(system_now_ns() - latest_.header().stamp_ns());
    return taken;
  }

  /// Blocks until a sample is waiting to be polled or `timeout_ns` passed (lock-step exchanges only).
  bool wait_for_data(int64_t timeout_ns) { return reader_.wait_for_data(timeout_ns); }

  bool has_sample() const { return has_sample_; }
  /// The newest sample received so far (valid when has_sample()).
  const T& latest() const { return latest_; }
  /// Time since the newest sample arrived, on the monotonic clock; huge when none arrived.
  int64_t age_ns(int64_t now_mono_ns) const {
    return has_sample_ ? now_mono_ns - latest_receive_mono_ns_ : INT64_MAX;
  }

  const std::string& topic_name() const { return topic_name_; }
  const SequenceTracker& stats() const { return tracker_; }
  /// Age of the newest sample at each poll (source stamp to now, CLOCK_REALTIME).
  const DurationHistogram& age() const { return age_; }
  const Reader<T>& reader() const { return reader_; }

 private:
  std::string topic_name_;
  Reader<T> reader_;
  T incoming_;
  T latest_;
  bool has_sample_ = false;
  int64_t latest_receive_mono_ns_ = 0;
  SequenceTracker tracker_;
  DurationHistogram age_;
};

}  // namespace teleop::transport
