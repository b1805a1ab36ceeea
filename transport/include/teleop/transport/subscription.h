#pragma once
// A reader plus reception statistics: the loop calls `poll()` once per cycle to drain what
// arrived, and reads the newest sample with `latest()`. The stream follows one writer at a time
// (common/stream_session.h): a restarted peer is followed from its first sample, another writer
// is refused while the followed one talks, and no sequence number can hold the stream.

#include <cstdint>
#include <string>
#include <utility>

#include "teleop/common/clock.h"
#include "teleop/common/sequence_tracker.h"
#include "teleop/common/stream_session.h"
#include "teleop/transport/participant.h"

namespace teleop::transport {

template <typename T>
class Subscription {
 public:
  /// Setup time: creates the reader. `policy` says when another writer may take the stream over.
  /// The node needs a writer on the topic (it is awaited, see mark_optional()).
  Subscription(Participant& participant, const TopicSpec<T>& topic, StreamSessionPolicy policy = {})
      : topic_name_(topic.name), reader_(participant.make_reader(topic)), session_(policy) {
    reader_.set_awaited(true);
  }

  /// The node works without a writer on this topic (an alternative or optional input): nobody
  /// is told it waits for one. Setup time.
  void mark_optional() { reader_.set_awaited(false); }

  /// Takes every sample that arrived since the last poll, updates the statistics and keeps the
  /// newest of the followed writer as `latest()`. Non-blocking and real-time safe. Returns the
  /// number of samples that became the newest (0: `latest()` is unchanged).
  int poll() {
    int newest = 0;
    int64_t reception_ns = 0;
    const int64_t now_mono_ns = monotonic_now_ns();
    while (reader_.take_next(incoming_, reception_ns, writer_)) {
      const auto& header = incoming_.header();
      const Admission admission = session_.admit(writer_, header.seq(), now_mono_ns);
      if (admission == Admission::kOtherWriter || admission == Admission::kSequenceJump) continue;
      if (admission == Admission::kNewSession) tracker_.begin_session();
      // latency of the transport itself: source stamp to DDS reception, not to this poll
      tracker_.on_sample(header.seq(), header.stamp_ns(), reception_ns);
      smooth_latency(reception_ns - header.stamp_ns());
      if (is_newest(admission)) {
        // swap, not copy: both buffers keep their capacity, nothing is allocated
        std::swap(latest_, incoming_);
        has_sample_ = true;
        latest_receive_mono_ns_ = now_mono_ns;
        ++newest;
      }
    }
    // what the loop works with: how old the newest sample is now
    if (has_sample_) age_.record(system_now_ns() - latest_.header().stamp_ns());
    reader_.report_flow(tracker_.received(), tracker_.lost(), latency_smoothed_ns_);
    return newest;
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
  /// The followed writer's session (0 before the first sample) and what was refused.
  const StreamSession& session() const { return session_; }
  /// Age of the newest sample at each poll (source stamp to now, CLOCK_REALTIME).
  const DurationHistogram& age() const { return age_; }
  const Reader<T>& reader() const { return reader_; }

 private:
  // an exponential average over ~64 samples: what NodeStatus shows as the flow's latency now
  void smooth_latency(int64_t latency_ns) {
    latency_smoothed_ns_ = tracker_.received() == 1 ? latency_ns : latency_smoothed_ns_ + (latency_ns - latency_smoothed_ns_) / 64;
  }

  std::string topic_name_;
  Reader<T> reader_;
  StreamSession session_;
  WriterId writer_;
  T incoming_;
  T latest_;
  bool has_sample_ = false;
  int64_t latest_receive_mono_ns_ = 0;
  SequenceTracker tracker_;
  DurationHistogram age_;
  int64_t latency_smoothed_ns_ = 0;
};

}  // namespace teleop::transport
