#include "teleop/common/sequence_tracker.h"

namespace teleop {

void SequenceTracker::begin_session() {
  if (session_received_ == 0) return;
  expected_before_ += last_seq_ - first_seq_ + 1;
  session_received_ = 0;
}

void SequenceTracker::on_sample(uint64_t seq, int64_t source_stamp_ns, int64_t receive_stamp_ns) {
  if (session_received_ == 0) {
    first_seq_ = last_seq_ = seq;
    if (received_ == 0) first_receive_ns_ = receive_stamp_ns;
    window_ = 1;
    ++sessions_;
  } else if (seq == last_seq_) {
    ++duplicates_;
    return;
  } else if (seq < last_seq_) {
    const uint64_t age = last_seq_ - seq;
    if (age < kWindow) {
      if ((window_ >> age) & 1u) {
        ++duplicates_;
        return;
      }
      window_ |= uint64_t{1} << age;
    }
    // an older sample arrived after a newer one; it still counts as received
    ++reordered_;
    if (seq < first_seq_) first_seq_ = seq;
  } else {
    const uint64_t advance = seq - last_seq_;
    if (advance > 1) gaps_.record(static_cast<int64_t>(advance - 1));
    window_ = (advance < kWindow ? window_ << advance : 0) | 1u;
    last_seq_ = seq;
  }
  ++received_;
  ++session_received_;
  last_receive_ns_ = receive_stamp_ns;
  latency_.record(receive_stamp_ns - source_stamp_ns);
}

uint64_t SequenceTracker::lost() const {
  const uint64_t exp = expected();
  return exp > received_ ? exp - received_ : 0;
}

double SequenceTracker::rate_hz() const {
  if (received_ < 2 || last_receive_ns_ <= first_receive_ns_) return 0.0;
  const double span_s = static_cast<double>(last_receive_ns_ - first_receive_ns_) * 1e-9;
  return static_cast<double>(received_ - 1) / span_s;
}

}  // namespace teleop
