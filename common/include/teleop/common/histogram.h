#pragma once
// Fixed-memory histogram of non-negative durations (ns) with bounded relative error,
// for latency and jitter percentiles inside real-time loops.

#include <array>
#include <cstdint>

namespace teleop {

/// Log-linear histogram: exact below 2^kSubBits ns, then kSubBuckets buckets per power of two,
/// so a percentile is off by at most 1/kSubBuckets (about 3 %). Records without allocating.
class DurationHistogram {
 public:
  static constexpr int kSubBits = 5;
  static constexpr int kSubBuckets = 1 << kSubBits;
  static constexpr int kOctaves = 64 - kSubBits;
  static constexpr int kBuckets = kSubBuckets * (kOctaves + 1);

  /// Adds one value; negative values count as 0. Real-time safe.
  void record(int64_t value_ns);
  /// Adds all counts of `other`.
  void merge(const DurationHistogram& other);
  void reset();

  uint64_t count() const { return count_; }
  int64_t min_ns() const { return count_ ? min_ns_ : 0; }
  int64_t max_ns() const { return count_ ? max_ns_ : 0; }
  double mean_ns() const { return count_ ? static_cast<double>(sum_ns_) / static_cast<double>(count_) : 0.0; }
  /// The value below which `fraction` (0..1) of the samples lie; 0 when empty.
  /// Returns the upper edge of the bucket, clamped to the exact maximum.
  int64_t percentile_ns(double fraction) const;

  /// Bucket index of a value (exposed for tests).
  static int bucket_of(uint64_t value_ns);
  /// Largest value that falls into `bucket`.
  static uint64_t upper_edge_of(int bucket);

 private:
  std::array<uint64_t, kBuckets> counts_{};
  uint64_t count_ = 0;
  int64_t min_ns_ = 0;
  int64_t max_ns_ = 0;
  // sum of all values; a 1 kHz loop recording 1 ms values overflows after ~290 years
  int64_t sum_ns_ = 0;
};

}  // namespace teleop
