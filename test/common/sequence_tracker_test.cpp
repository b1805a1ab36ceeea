#include "teleop/common/sequence_tracker.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <initializer_list>

namespace teleop {
namespace {

constexpr int64_t kMs = 1'000'000;

// feeds sequence numbers received 1 ms apart, each with 100 us latency
void feed(SequenceTracker& t, std::initializer_list<uint64_t> seqs, int64_t start_ns = 1'000 * kMs) {
  int64_t rx = start_ns;
  for (uint64_t s : seqs) {
    t.on_sample(s, rx - 100'000, rx);
    rx += kMs;
  }
}

TEST(SequenceTracker, ReportsZeroWhenNothingReceived) {
  const SequenceTracker t;
  EXPECT_EQ(t.received(), 0u);
  EXPECT_EQ(t.expected(), 0u);
  EXPECT_EQ(t.lost(), 0u);
  EXPECT_EQ(t.duplicates(), 0u);
  EXPECT_EQ(t.reordered(), 0u);
  EXPECT_EQ(t.rate_hz(), 0.0);
  EXPECT_EQ(t.latency().count(), 0u);
}

TEST(SequenceTracker, CountsNoLossWhenSequenceIsContiguous) {
  SequenceTracker t;
  for (uint64_t s = 1; s <= 100; ++s) t.on_sample(s, 0, 0);
  EXPECT_EQ(t.received(), 100u);
  EXPECT_EQ(t.expected(), 100u);
  EXPECT_EQ(t.lost(), 0u);
  EXPECT_EQ(t.first_seq(), 1u);
  EXPECT_EQ(t.last_seq(), 100u);
}

TEST(SequenceTracker, CountsLossFromGapsWhenSamplesAreMissing) {
  SequenceTracker t;
  feed(t, {1, 2, 5, 6, 10});  // 3, 4, 7, 8, 9 missing
  EXPECT_EQ(t.received(), 5u);
  EXPECT_EQ(t.expected(), 10u);
  EXPECT_EQ(t.lost(), 5u);
  EXPECT_EQ(t.duplicates(), 0u);
  EXPECT_EQ(t.reordered(), 0u);
}

TEST(SequenceTracker, ExpectedStartsAtFirstReceivedWhenJoiningLate) {
  SequenceTracker t;
  feed(t, {1000, 1001, 1003});
  EXPECT_EQ(t.first_seq(), 1000u);
  EXPECT_EQ(t.last_seq(), 1003u);
  EXPECT_EQ(t.expected(), 4u);
  EXPECT_EQ(t.lost(), 1u);  // samples before the first one are not counted as lost
}

TEST(SequenceTracker, CountsDuplicateWithoutReceivingItAgainWhenSameSeqRepeats) {
  SequenceTracker t;
  feed(t, {1, 2, 2, 3, 3, 3});
  EXPECT_EQ(t.received(), 3u);
  EXPECT_EQ(t.duplicates(), 3u);
  EXPECT_EQ(t.expected(), 3u);
  EXPECT_EQ(t.lost(), 0u);
  EXPECT_EQ(t.latency().count(), 3u);  // duplicates do not add latency samples
}

TEST(SequenceTracker, CountsDuplicateWhenAnOlderSampleArrivesAgain) {
  SequenceTracker t;
  feed(t, {1, 2, 3, 2, 1});
  EXPECT_EQ(t.duplicates(), 2u);
  EXPECT_EQ(t.reordered(), 0u);
  EXPECT_EQ(t.received(), 3u);
  EXPECT_EQ(t.expected(), 3u);
  EXPECT_EQ(t.lost(), 0u);
}

TEST(SequenceTracker, KeepsCountingLossWhenARepeatedOldSampleWouldHideIt) {
  SequenceTracker t;
  feed(t, {1, 3, 1});  // 2 never arrives; the repeated 1 must not stand in for it
  EXPECT_EQ(t.lost(), 1u);
  EXPECT_EQ(t.duplicates(), 1u);
  EXPECT_EQ(t.received(), 2u);
}

TEST(SequenceTracker, CountsLateArrivalOnceAndItsRepeatAsDuplicate) {
  SequenceTracker t;
  feed(t, {1, 3, 2, 2});
  EXPECT_EQ(t.reordered(), 1u);
  EXPECT_EQ(t.duplicates(), 1u);
  EXPECT_EQ(t.received(), 3u);
  EXPECT_EQ(t.lost(), 0u);
}

TEST(SequenceTracker, TellsLateArrivalFromDuplicateAfterALongGap) {
  SequenceTracker t;
  feed(t, {1, 200, 150, 150, 199});
  EXPECT_EQ(t.reordered(), 2u);   // 150 and 199 arrived late
  EXPECT_EQ(t.duplicates(), 1u);  // the second 150
  EXPECT_EQ(t.received(), 4u);
  EXPECT_EQ(t.expected(), 200u);
  EXPECT_EQ(t.lost(), 196u);
}

TEST(SequenceTracker, CreditsLateArrivalBackWhenReordered) {
  SequenceTracker t;
  feed(t, {1, 2, 4, 5});
  EXPECT_EQ(t.lost(), 1u);
  feed(t, {3}, 2'000 * kMs);  // 3 arrives late
  EXPECT_EQ(t.reordered(), 1u);
  EXPECT_EQ(t.received(), 5u);
  EXPECT_EQ(t.expected(), 5u);
  EXPECT_EQ(t.lost(), 0u);
  EXPECT_EQ(t.last_seq(), 5u);  // an old sample does not move the newest one back
}

TEST(SequenceTracker, ExtendsFirstSeqWhenSampleOlderThanFirstArrivesLate) {
  SequenceTracker t;
  feed(t, {10, 11, 12, 8});
  EXPECT_EQ(t.first_seq(), 8u);
  EXPECT_EQ(t.last_seq(), 12u);
  EXPECT_EQ(t.expected(), 5u);
  EXPECT_EQ(t.received(), 4u);
  EXPECT_EQ(t.lost(), 1u);  // 9 is missing
  EXPECT_EQ(t.reordered(), 1u);
}

TEST(SequenceTracker, MeasuresRateFromReceiveStampsWhenSamplesArriveAtFixedPeriod) {
  SequenceTracker t;
  // 1001 samples 1 ms apart: 1000 intervals in 1 s
  for (uint64_t s = 1; s <= 1001; ++s) {
    const int64_t rx = 5 * 1'000 * kMs + static_cast<int64_t>(s - 1) * kMs;
    t.on_sample(s, rx, rx);
  }
  EXPECT_DOUBLE_EQ(t.rate_hz(), 1000.0);
  EXPECT_EQ(t.last_receive_ns(), 5 * 1'000 * kMs + 1000 * kMs);
}

TEST(SequenceTracker, RateCountsReceivedSamplesNotSequenceSpanWhenSamplesAreLost) {
  SequenceTracker t;
  // every other sample lost: 11 received over 1 s (stamped 100 ms apart)
  for (uint64_t i = 0; i <= 10; ++i) t.on_sample(1 + 2 * i, 0, static_cast<int64_t>(i) * 100 * kMs);
  EXPECT_DOUBLE_EQ(t.rate_hz(), 10.0);
  EXPECT_EQ(t.lost(), 10u);
}

TEST(SequenceTracker, RateIsZeroWhenOnlyOneSampleOrNoTimeSpan) {
  SequenceTracker one;
  one.on_sample(1, 0, 1000);
  EXPECT_EQ(one.rate_hz(), 0.0);
  SequenceTracker same_time;
  same_time.on_sample(1, 0, 1000);
  same_time.on_sample(2, 0, 1000);
  EXPECT_EQ(same_time.rate_hz(), 0.0);
}

TEST(SequenceTracker, RecordsLatencyAsReceiveMinusSourceStamp) {
  SequenceTracker t;
  t.on_sample(1, 1'000'000, 1'000'250);   // 250 ns
  t.on_sample(2, 2'000'000, 2'000'010);   // 10 ns
  t.on_sample(3, 3'000'000, 3'000'020);   // 20 ns
  EXPECT_EQ(t.latency().count(), 3u);
  EXPECT_EQ(t.latency().min_ns(), 10);
  EXPECT_EQ(t.latency().max_ns(), 250);
  EXPECT_EQ(t.latency().percentile_ns(0.5), 20);
  EXPECT_DOUBLE_EQ(t.latency().mean_ns(), 280.0 / 3.0);
}

TEST(SequenceTracker, RecordsZeroLatencyWhenClocksMakeItNegative) {
  SequenceTracker t;
  t.on_sample(1, 5'000, 4'000);  // receiver clock behind the sender's
  EXPECT_EQ(t.latency().count(), 1u);
  EXPECT_EQ(t.latency().max_ns(), 0);
}

}  // namespace
}  // namespace teleop

namespace teleop {
namespace {

TEST(SequenceTrackerSessions, AddsUpTheSessionsOfARestartedWriter) {
  SequenceTracker t;
  for (uint64_t s = 1; s <= 8000; ++s) t.on_sample(s, 0, 0);
  // the writer restarted: its successor numbers from 1 again, and loses samples 3 and 4
  t.begin_session();
  for (uint64_t s : {1, 2, 5, 6}) t.on_sample(s, 0, 0);
  EXPECT_EQ(t.sessions(), 2u);
  EXPECT_EQ(t.received(), 8004u);
  EXPECT_EQ(t.expected(), 8006u);
  EXPECT_EQ(t.lost(), 2u);
  EXPECT_EQ(t.first_seq(), 1u);
  EXPECT_EQ(t.last_seq(), 6u);
  EXPECT_EQ(t.duplicates(), 0u);
}

TEST(SequenceTrackerSessions, ABeginWithoutSamplesChangesNothing) {
  SequenceTracker t;
  t.begin_session();
  feed(t, {1, 2, 3});
  t.begin_session();
  t.begin_session();
  feed(t, {1});
  EXPECT_EQ(t.sessions(), 2u);
  EXPECT_EQ(t.expected(), 4u);
  EXPECT_EQ(t.lost(), 0u);
}

}  // namespace
}  // namespace teleop
