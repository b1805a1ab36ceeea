#pragma once
// A writer plus its preallocated sample and header bookkeeping: the loop fills the payload,
// `publish()` stamps sequence number and times and sends.

#include <cstdint>
#include <string>

#include "teleop/common/clock.h"
#include "teleop/common/histogram.h"
#include "teleop/transport/participant.h"

namespace teleop::transport {

template <typename T>
class Publication {
 public:
  /// Setup time: creates the writer. `source` (the node name) goes into every header.
  Publication(Participant& participant, const TopicSpec<T>& topic, const std::string& source)
      : topic_name_(topic.name), writer_(participant.make_writer(topic)) {
    sample_.header().source(source.c_str());
  }

  /// The sample to fill before publishing; keeps its contents between cycles.
  T& sample() { return sample_; }

  /// Stamps the header (next sequence number, system and monotonic time) and sends.
  /// Real-time safe. Returns false if DDS refused the sample (counted).
  bool publish() {
    sample_.header().seq(++sent_);
    return stamp_and_write();
  }

  /// Sends the last published sample again, with its sequence number and fresh times: for a
  /// reliable exchange whose first sample may have gone out before the peer's reader was
  /// matched (volatile durability keeps nothing for it). Readers see a duplicate, not a gap.
  bool resend() { return stamp_and_write(); }

  /// Waits up to `timeout_ns` for reliable readers to acknowledge what was published (shutdown).
  bool wait_for_acknowledgments(int64_t timeout_ns) { return writer_.wait_for_acknowledgments(timeout_ns); }

  const std::string& topic_name() const { return topic_name_; }
  uint64_t sent() const { return sent_; }
  uint64_t failed() const { return failed_; }
  /// How long each write took (the send of a best-effort stream included): a reader or a
  /// discovery storm that made a write wait shows here.
  const DurationHistogram& write_time() const { return write_time_; }
  int32_t matched() const { return writer_.matched(); }
  /// The writer's GUID (what a reader's FlowStatus.following_writer names when it follows us).
  WriterId writer_id() const { return writer_.id(); }

 private:
  // stamps the header's times (not its sequence number) and sends; a refusal is counted
  bool stamp_and_write() {
    auto& header = sample_.header();
    header.stamp_ns(system_now_ns());
    header.stamp_mono_ns(monotonic_now_ns());
    const bool written = writer_.write(sample_);
    write_time_.record(monotonic_now_ns() - header.stamp_mono_ns());
    if (written) return true;
    ++failed_;
    return false;
  }

  std::string topic_name_;
  Writer<T> writer_;
  T sample_;
  uint64_t sent_ = 0;
  uint64_t failed_ = 0;
  DurationHistogram write_time_;
};

}  // namespace teleop::transport
