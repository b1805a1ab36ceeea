#include "teleop/common/histogram.h"

#include <algorithm>
#include <bit>
#include <cmath>

namespace teleop {

int DurationHistogram::bucket_of(uint64_t value_ns) {
  if (value_ns < static_cast<uint64_t>(kSubBuckets)) {
    return static_cast<int>(value_ns);
  }
  // octave k >= 1 covers [2^(k+kSubBits-1), 2^(k+kSubBits)) split into kSubBuckets equal parts
  const int msb = 63 - std::countl_zero(value_ns);
  const int octave = msb - kSubBits + 1;
  const int shift = msb - kSubBits;
  const int sub = static_cast<int>((value_ns >> shift) & (kSubBuckets - 1));
  return octave * kSubBuckets + sub;
}

uint64_t DurationHistogram::upper_edge_of(int bucket) {
  if (bucket < kSubBuckets) {
    return static_cast<uint64_t>(bucket);
  }
  const int octave = bucket / kSubBuckets;
  const uint64_t sub = static_cast<uint64_t>(bucket % kSubBuckets);
  const int shift = octave - 1;
  const uint64_t lower = (static_cast<uint64_t>(kSubBuckets) + sub) << shift;
  return lower + ((uint64_t{1} << shift) - 1);
}

void DurationHistogram::record(int64_t value_ns) {
  const int64_t v = std::max<int64_t>(value_ns, 0);
  ++counts_[static_cast<size_t>(bucket_of(static_cast<uint64_t>(v)))];
  if (count_ == 0 || v < min_ns_) min_ns_ = v;
  if (count_ == 0 || v > max_ns_) max_ns_ = v;
  ++count_;
  sum_ns_ += v;
}

void DurationHistogram::merge(const DurationHistogram& other) {
  if (other.count_ == 0) return;
  for (size_t i = 0; i < counts_.size(); ++i) counts_[i] += other.counts_[i];
  min_ns_ = count_ ? std::min(min_ns_, other.min_ns_) : other.min_ns_;
  max_ns_ = count_ ? std::max(max_ns_, other.max_ns_) : other.max_ns_;
  count_ += other.count_;
  sum_ns_ += other.sum_ns_;
}

void DurationHistogram::reset() { *this = DurationHistogram{}; }

int64_t DurationHistogram::percentile_ns(double fraction) const {
  if (count_ == 0) return 0;
  const double clamped = std::clamp(fraction, 0.0, 1.0);
  // rank of the sample we want, 1-based
  const auto rank = std::max<uint64_t>(1, static_cast<uint64_t>(std::ceil(clamped * static_cast<double>(count_))));
  uint64_t seen = 0;
  for (int b = 0; b < kBuckets; ++b) {
    seen += counts_[static_cast<size_t>(b)];
    if (seen >= rank) {
      return std::min<int64_t>(static_cast<int64_t>(upper_edge_of(b)), max_ns_);
    }
  }
  return max_ns_;
}

}  // namespace teleop
