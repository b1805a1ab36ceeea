#pragma once
// Per-stream reception statistics computed from sample sequence numbers and stamps.

#include <cstdint>

#include "teleop/common/histogram.h"

namespace teleop {

/// Tracks a stream as seen by a reader: received, lost (sequence gaps), duplicated or reordered
/// samples, one-way latency, and the receive rate. Sequence numbers count within a session (one
/// writer, stream_session.h); the counts add up over the sessions. Real-time safe.
class SequenceTracker {
 public:
  /// The next sample starts a new session: its sequence numbers are not compared with this
  /// session's, whose counts are kept.
  void begin_session();

  /// Records a received sample: its sequence number, its source stamp and the local receive
  /// time, both on the same clock (the latency is their difference).
  void on_sample(uint64_t seq, int64_t source_stamp_ns, int64_t receive_stamp_ns);

  uint64_t received() const { return received_; }
  /// The current session's first and last sequence numbers received.
  uint64_t first_seq() const { return first_seq_; }
  uint64_t last_seq() const { return last_seq_; }
  /// Samples the writers sent between the first and the last one received, summed over sessions.
  uint64_t expected() const { return expected_before_ + (session_received_ ? last_seq_ - first_seq_ + 1 : 0); }
  /// Sessions seen (writers followed in turn).
  uint64_t sessions() const { return sessions_; }
  /// Samples never received within [first_seq, last_seq] (late arrivals are credited back).
  uint64_t lost() const;
  uint64_t duplicates() const { return duplicates_; }
  uint64_t reordered() const { return reordered_; }
  /// Receive rate over the span between the first and last sample received, in Hz.
  double rate_hz() const;
  const DurationHistogram& latency() const { return latency_; }
  /// Lengths of the sequence gaps seen on arrival (runs of samples missed in a row).
  const DurationHistogram& gaps() const { return gaps_; }
  int64_t last_receive_ns() const { return last_receive_ns_; }

 private:
  uint64_t received_ = 0;
  uint64_t session_received_ = 0;
  uint64_t expected_before_ = 0;
  uint64_t sessions_ = 0;
  uint64_t first_seq_ = 0;
  uint64_t last_seq_ = 0;
  uint64_t duplicates_ = 0;
  uint64_t reordered_ = 0;
  int64_t first_receive_ns_ = 0;
  int64_t last_receive_ns_ = 0;
  // receipt bits of the newest kWindow sequence numbers: bit i set = last_seq_ - i was received,
  // so that a repeated older sample counts as a duplicate, not as a late arrival
  static constexpr uint64_t kWindow = 64;
  uint64_t window_ = 0;
  DurationHistogram latency_;
  DurationHistogram gaps_;
};

}  // namespace teleop
