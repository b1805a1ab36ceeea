#include "teleop/common/histogram.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

namespace teleop {
namespace {

constexpr double kRelTol = 1.0 / DurationHistogram::kSubBuckets;

// a spread of values from every octave, with the edges of each octave and its neighbours
std::vector<uint64_t> probe_values() {
  std::vector<uint64_t> v;
  for (uint64_t x = 0; x < 256; ++x) v.push_back(x);
  for (int bit = 8; bit < 64; ++bit) {
    const uint64_t p = uint64_t{1} << bit;
    for (uint64_t d : {uint64_t{0}, uint64_t{1}, uint64_t{2}, p / 3, p / 2, p - 1}) {
      v.push_back(p + d);
      v.push_back(p - 1 - (d < p ? d : 0));
    }
  }
  v.push_back(std::numeric_limits<uint64_t>::max());
  return v;
}

TEST(DurationHistogram, BucketOfIsExactBelowSubBucketCount) {
  for (uint64_t v = 0; v < static_cast<uint64_t>(DurationHistogram::kSubBuckets); ++v) {
    EXPECT_EQ(DurationHistogram::bucket_of(v), static_cast<int>(v));
    EXPECT_EQ(DurationHistogram::upper_edge_of(static_cast<int>(v)), v);
  }
}

TEST(DurationHistogram, UpperEdgeBoundsEveryValueOfItsBucketWhenRoundTripped) {
  for (uint64_t v : probe_values()) {
    const int b = DurationHistogram::bucket_of(v);
    ASSERT_GE(b, 0) << v;
    ASSERT_LT(b, DurationHistogram::kBuckets) << v;
    const uint64_t edge = DurationHistogram::upper_edge_of(b);
    // the value lies in its bucket: not above the bucket's upper edge, above the previous one
    EXPECT_GE(edge, v) << "value " << v << " bucket " << b;
    if (b > 0) {
      EXPECT_LT(DurationHistogram::upper_edge_of(b - 1), v) << "value " << v << " bucket " << b;
    }
    // the upper edge is itself in the bucket
    EXPECT_EQ(DurationHistogram::bucket_of(edge), b) << "edge " << edge;
    // relative error bounded by one sub-bucket
    if (v > 0) {
      EXPECT_LE(static_cast<double>(edge - v) / static_cast<double>(v), kRelTol) << v;
    }
  }
}

TEST(DurationHistogram, BucketEdgesAreStrictlyMonotonicOverAllBuckets) {
  for (int b = 1; b < DurationHistogram::kBuckets; ++b) {
    ASSERT_LT(DurationHistogram::upper_edge_of(b - 1), DurationHistogram::upper_edge_of(b)) << "bucket " << b;
    // adjacent buckets tile the value range without gaps
    ASSERT_EQ(DurationHistogram::bucket_of(DurationHistogram::upper_edge_of(b - 1) + 1), b) << "bucket " << b;
  }
  EXPECT_EQ(DurationHistogram::upper_edge_of(DurationHistogram::kBuckets - 1), std::numeric_limits<uint64_t>::max());
}

TEST(DurationHistogram, BucketOfIsMonotonicInTheValue) {
  int previous = -1;
  for (uint64_t v = 0; v < (uint64_t{1} << 16); ++v) {
    const int b = DurationHistogram::bucket_of(v);
    ASSERT_GE(b, previous) << v;
    ASSERT_LE(b, previous + 1) << v;
    previous = b;
  }
}

TEST(DurationHistogram, ReturnsZeroForEverythingWhenEmpty) {
  const DurationHistogram h;
  EXPECT_EQ(h.count(), 0u);
  EXPECT_EQ(h.min_ns(), 0);
  EXPECT_EQ(h.max_ns(), 0);
  EXPECT_EQ(h.mean_ns(), 0.0);
  EXPECT_EQ(h.percentile_ns(0.0), 0);
  EXPECT_EQ(h.percentile_ns(0.5), 0);
  EXPECT_EQ(h.percentile_ns(1.0), 0);
}

TEST(DurationHistogram, TracksMinMaxMeanExactlyWhenRecording) {
  DurationHistogram h;
  for (int64_t v : {1000, 250, 123'456'789, 7, 5000}) h.record(v);
  EXPECT_EQ(h.count(), 5u);
  EXPECT_EQ(h.min_ns(), 7);
  EXPECT_EQ(h.max_ns(), 123'456'789);
  EXPECT_DOUBLE_EQ(h.mean_ns(), (1000.0 + 250.0 + 123'456'789.0 + 7.0 + 5000.0) / 5.0);
}

TEST(DurationHistogram, CountsNegativeValuesAsZeroWhenRecorded) {
  DurationHistogram h;
  h.record(-5);
  h.record(-1'000'000);
  h.record(10);
  EXPECT_EQ(h.count(), 3u);
  EXPECT_EQ(h.min_ns(), 0);
  EXPECT_EQ(h.max_ns(), 10);
  EXPECT_DOUBLE_EQ(h.mean_ns(), 10.0 / 3.0);
  EXPECT_EQ(h.percentile_ns(0.5), 0);
  EXPECT_EQ(h.percentile_ns(0.6), 0);
  EXPECT_EQ(h.percentile_ns(1.0), 10);
}

TEST(DurationHistogram, GivesExactPercentilesWhenValuesAreSmall) {
  DurationHistogram h;
  for (int64_t v = 1; v <= 20; ++v) h.record(v);
  EXPECT_EQ(h.percentile_ns(0.0), 1);
  EXPECT_EQ(h.percentile_ns(0.05), 1);
  EXPECT_EQ(h.percentile_ns(0.5), 10);
  EXPECT_EQ(h.percentile_ns(0.51), 11);
  EXPECT_EQ(h.percentile_ns(1.0), 20);
  // fractions outside [0, 1] are clamped
  EXPECT_EQ(h.percentile_ns(-1.0), 1);
  EXPECT_EQ(h.percentile_ns(2.0), 20);
}

TEST(DurationHistogram, PercentilesOfUniformDistributionWithinRelativeErrorWhenValuesAreLarge) {
  // 1..100000 us in ns: the exact p-th percentile is ceil(p * n) * 1000
  DurationHistogram h;
  constexpr int64_t n = 100'000;
  for (int64_t i = 1; i <= n; ++i) h.record(i * 1000);
  for (double p : {0.01, 0.1, 0.25, 0.5, 0.75, 0.9, 0.99, 0.999, 1.0}) {
    const double exact = std::ceil(p * static_cast<double>(n)) * 1000.0;
    const auto got = static_cast<double>(h.percentile_ns(p));
    EXPECT_GE(got, exact) << "p=" << p;  // the upper edge never under-reports
    EXPECT_LE((got - exact) / exact, kRelTol) << "p=" << p;
  }
  EXPECT_EQ(h.percentile_ns(1.0), n * 1000);  // clamped to the exact maximum
}

TEST(DurationHistogram, PercentilesOfShuffledExponentialSamplesWithinRelativeError) {
  std::mt19937_64 rng(42);
  std::exponential_distribution<double> dist(1.0 / 200'000.0);  // mean 200 us
  std::vector<int64_t> values(50'000);
  for (auto& v : values) v = static_cast<int64_t>(dist(rng)) + 1;
  DurationHistogram h;
  for (int64_t v : values) h.record(v);
  std::vector<int64_t> sorted = values;
  std::sort(sorted.begin(), sorted.end());
  for (double p : {0.5, 0.9, 0.99, 0.999}) {
    const auto rank = static_cast<size_t>(std::ceil(p * static_cast<double>(sorted.size())));
    const auto exact = static_cast<double>(sorted[rank - 1]);
    const auto got = static_cast<double>(h.percentile_ns(p));
    EXPECT_GE(got, exact) << "p=" << p;
    EXPECT_LE((got - exact) / exact, kRelTol) << "p=" << p;
  }
  EXPECT_EQ(h.max_ns(), sorted.back());
  EXPECT_EQ(h.min_ns(), sorted.front());
}

TEST(DurationHistogram, PercentileIsClampedToMaxWhenBucketEdgeExceedsIt) {
  DurationHistogram h;
  h.record(1'000'001);  // its bucket's upper edge is larger
  ASSERT_GT(DurationHistogram::upper_edge_of(DurationHistogram::bucket_of(1'000'001)), 1'000'001u);
  EXPECT_EQ(h.percentile_ns(0.5), 1'000'001);
  EXPECT_EQ(h.percentile_ns(1.0), 1'000'001);
}

TEST(DurationHistogram, MergeEqualsRecordingEverythingInOne) {
  DurationHistogram a;
  DurationHistogram b;
  DurationHistogram all;
  for (int64_t i = 0; i < 1000; ++i) {
    const int64_t v = (i * 7919) % 100'000 + 50;
    (i % 3 == 0 ? a : b).record(v);
    all.record(v);
  }
  a.merge(b);
  EXPECT_EQ(a.count(), all.count());
  EXPECT_EQ(a.min_ns(), all.min_ns());
  EXPECT_EQ(a.max_ns(), all.max_ns());
  EXPECT_DOUBLE_EQ(a.mean_ns(), all.mean_ns());
  for (double p : {0.0, 0.1, 0.5, 0.9, 0.99, 1.0}) EXPECT_EQ(a.percentile_ns(p), all.percentile_ns(p)) << p;
}

TEST(DurationHistogram, MergeTakesOtherMinMaxWhenThisIsEmpty) {
  DurationHistogram empty;
  DurationHistogram other;
  other.record(500);
  other.record(900);
  empty.merge(other);
  EXPECT_EQ(empty.count(), 2u);
  EXPECT_EQ(empty.min_ns(), 500);  // not the 0 of the empty histogram
  EXPECT_EQ(empty.max_ns(), 900);
  EXPECT_DOUBLE_EQ(empty.mean_ns(), 700.0);
}

TEST(DurationHistogram, MergeOfEmptyHistogramChangesNothing) {
  DurationHistogram h;
  h.record(300);
  h.record(100);
  h.merge(DurationHistogram{});
  EXPECT_EQ(h.count(), 2u);
  EXPECT_EQ(h.min_ns(), 100);
  EXPECT_EQ(h.max_ns(), 300);
  EXPECT_DOUBLE_EQ(h.mean_ns(), 200.0);
}

TEST(DurationHistogram, ResetEmptiesTheHistogram) {
  DurationHistogram h;
  h.record(12345);
  h.reset();
  EXPECT_EQ(h.count(), 0u);
  EXPECT_EQ(h.percentile_ns(0.5), 0);
  h.record(20);
  EXPECT_EQ(h.min_ns(), 20);
  EXPECT_EQ(h.percentile_ns(1.0), 20);
}

}  // namespace
}  // namespace teleop
