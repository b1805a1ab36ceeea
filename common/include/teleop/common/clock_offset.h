#pragma once
// How far a peer's CLOCK_REALTIME stamps are from ours, learnt from its samples alone: the
// smallest apparent delay (reception on our clock minus the sender's stamp) over the last
// kBuckets seconds. With the peer's clock ahead by D and the fastest one-way latency L it is
// L - D: a sample's delay beyond its writer's fastest is then `apparent - estimate`, whatever D is,
// so that a stale command is judged without assuming synchronised clocks (docs/clocks.md). The
// two directions of a pair give D itself: D = (estimate_at_A - estimate_at_B) / 2 as seen from B.
//
// A minimum per one-second bucket of the monotonic clock, kept for kBuckets buckets: a clock
// that steps or drifts is followed within kBuckets seconds. Real-time safe (no allocation).

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>

namespace teleop {

class ClockOffsetEstimate {
 public:
  static constexpr int kBuckets = 10;
  static constexpr int64_t kBucketNs = 1'000'000'000;

  /// A sample's apparent delay [ns] (reception minus stamp, may be negative), seen at `now_mono_ns`.
  void add(int64_t apparent_ns, int64_t now_mono_ns) {
    const int64_t bucket = now_mono_ns / kBucketNs;
    Bucket& b = buckets_[static_cast<size_t>(bucket % kBuckets)];
    if (b.index != bucket) b = {bucket, apparent_ns};
    b.min_ns = std::min(b.min_ns, apparent_ns);
    newest_bucket_ = bucket;
    ++samples_;
  }
  /// Forgets everything (a new writer may live on another host).
  void reset() { *this = ClockOffsetEstimate{}; }

  bool valid() const { return samples_ > 0; }
  /// The smallest apparent delay of the last kBuckets buckets [ns]; 0 before the first sample.
  int64_t estimate_ns() const {
    int64_t best = std::numeric_limits<int64_t>::max();
    for (const Bucket& b : buckets_) {
      if (b.index > newest_bucket_ - kBuckets && b.index <= newest_bucket_) best = std::min(best, b.min_ns);
    }
    return valid() ? best : 0;
  }

 private:
  struct Bucket {
    int64_t index = std::numeric_limits<int64_t>::min();
    int64_t min_ns = std::numeric_limits<int64_t>::max();
  };
  std::array<Bucket, kBuckets> buckets_{};
  int64_t newest_bucket_ = 0;
  uint64_t samples_ = 0;
};

}  // namespace teleop
