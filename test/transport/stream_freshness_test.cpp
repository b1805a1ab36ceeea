#include "teleop/transport/stream_freshness.h"

#include <gtest/gtest.h>

#include <atomic>
#include <thread>

namespace teleop::transport {
namespace {

constexpr int64_t kMs = 1'000'000;
constexpr int64_t kLease = 250 * kMs;
constexpr int64_t kDeadline = 5 * kMs;

// a configured freshness, as a stream reader has it
struct Configured : StreamFreshness {
  Configured() { configure(kLease, kDeadline); }
};

TEST(StreamFreshness, IsOffUntilConfigured) {
  StreamFreshness f;
  EXPECT_FALSE(f.enabled());
  f.configure(kLease, kDeadline);
  EXPECT_TRUE(f.enabled());
  EXPECT_EQ(f.lease_ns(), kLease);
}

TEST(StreamFreshness, WithoutLeaseOrDeadlineNothingLapsesOrIsMissed) {
  StreamFreshness f;
  f.configure(0, 0);
  EXPECT_TRUE(f.enabled());
  EXPECT_EQ(f.lease_ns(), INT64_MAX);
  EXPECT_EQ(f.deadline_ns(), 0);
  f.on_arrival(kMs);
  EXPECT_EQ(f.alive(100'000 * kMs, 1), 1);
  EXPECT_EQ(f.lapses(100'000 * kMs), 0u);
  EXPECT_EQ(f.deadline_missed(100'000 * kMs), 0u);
  f.on_arrival(200'000 * kMs);
  EXPECT_EQ(f.lapses(200'000 * kMs), 0u);
  EXPECT_EQ(f.deadline_missed(200'000 * kMs), 0u);
}

TEST(StreamFreshness, CountsNothingBeforeTheFirstSample) {
  Configured f;
  EXPECT_EQ(f.alive(10'000 * kMs, 1), 0);
  EXPECT_EQ(f.lapses(10'000 * kMs), 0u);
  EXPECT_EQ(f.deadline_missed(10'000 * kMs), 0u);
}

TEST(StreamFreshness, AStreamAtRateIsAliveAndMissesNothing) {
  Configured f;
  for (int64_t t = 1; t <= 1000; ++t) f.on_arrival(t * kMs);
  EXPECT_EQ(f.alive(1000 * kMs + kMs / 2, 1), 1);
  EXPECT_EQ(f.lapses(1000 * kMs + kMs / 2), 0u);
  EXPECT_EQ(f.deadline_missed(1000 * kMs + kMs / 2), 0u);
}

TEST(StreamFreshness, CountsEveryWholeDeadlinePeriodOfASilence) {
  Configured f;
  f.on_arrival(100 * kMs);
  // during the silence: the periods gone so far
  EXPECT_EQ(f.deadline_missed(104 * kMs), 0u);
  EXPECT_EQ(f.deadline_missed(111 * kMs), 2u);
  // the next sample ends it: 12 ms = two whole periods, kept
  f.on_arrival(112 * kMs);
  EXPECT_EQ(f.deadline_missed(113 * kMs), 2u);
  EXPECT_EQ(f.deadline_missed(118 * kMs), 3u);
}

TEST(StreamFreshness, ALeaseWithoutSampleIsALapseCountedOnce) {
  Configured f;
  f.on_arrival(kMs);
  EXPECT_EQ(f.alive(kMs + kLease, 1), 1);
  EXPECT_EQ(f.alive(2 * kMs + kLease, 1), 0);
  EXPECT_EQ(f.lapses(2 * kMs + kLease), 1u);
  EXPECT_EQ(f.lapses(kMs + 10 * kLease), 1u) << "a long silence is one lapse";
  // the writer comes back: alive again, the lapse stays counted
  f.on_arrival(kMs + 10 * kLease);
  EXPECT_EQ(f.alive(2 * kMs + 10 * kLease, 1), 1);
  EXPECT_EQ(f.lapses(2 * kMs + 10 * kLease), 1u);
}

TEST(StreamFreshness, AWriterLeavingWhileAliveIsNoLapse) {
  Configured f;
  f.on_arrival(kMs);
  f.on_unmatched(2 * kMs);
  EXPECT_EQ(f.alive(3 * kMs, 0), 0);
  EXPECT_EQ(f.lapses(10 * kLease), 0u);
  EXPECT_EQ(f.deadline_missed(10 * kLease), 0u);
}

TEST(StreamFreshness, ALapseBeforeTheWriterLeftStaysCounted) {
  Configured f;
  f.on_arrival(kMs);
  // silent for a lease, then the participant lease removes the writer
  f.on_unmatched(kMs + 3000 * kMs);
  EXPECT_EQ(f.lapses(kMs + 3001 * kMs), 1u);
  EXPECT_EQ(f.lapses(kMs + 9000 * kMs), 1u);
  EXPECT_EQ(f.deadline_missed(kMs + 9000 * kMs), 600u) << "3 s of 5 ms periods, then nobody to miss";
  EXPECT_EQ(f.alive(kMs + 9000 * kMs, 0), 0);
}

TEST(StreamFreshness, AliveNeedsAMatchedWriter) {
  Configured f;
  f.on_arrival(kMs);
  EXPECT_EQ(f.alive(2 * kMs, 1), 1);
  EXPECT_EQ(f.alive(2 * kMs, 0), 0);
}

TEST(StreamFreshness, ArrivalsReportedOutOfOrderDoNotRunTimeBack) {
  Configured f;
  f.on_arrival(100 * kMs);
  f.on_arrival(99 * kMs);  // another receive thread, a moment behind
  EXPECT_EQ(f.deadline_missed(104 * kMs), 0u);
  EXPECT_EQ(f.lapses(104 * kMs), 0u);
  f.on_arrival(101 * kMs);
  EXPECT_EQ(f.deadline_missed(101 * kMs), 0u);
}

TEST(StreamFreshness, QueriesFromAnotherThreadNeverGoBackwards) {
  // one thread reports arrivals with silences of a lease now and then, another asks: what it
  // sees must never decrease (the follower compares lapses before and after a command)
  Configured f;
  std::atomic<int64_t> clock{kMs};
  std::atomic<bool> done{false};
  std::thread arrivals([&] {
    for (int i = 0; i < 200'000; ++i) {
      const int64_t step = i % 1000 == 999 ? kLease + kMs : kMs;
      const int64_t t = clock.fetch_add(step) + step;
      f.on_arrival(t);
    }
    done = true;
  });
  uint64_t last_lapses = 0;
  uint64_t last_missed = 0;
  while (!done) {
    // the query's "now" may be taken before an arrival is reported, as in a real loop
    const int64_t now = clock.load();
    const uint64_t lapses = f.lapses(now);
    const uint64_t missed = f.deadline_missed(now);
    ASSERT_GE(lapses, last_lapses);
    ASSERT_GE(missed, last_missed);
    last_lapses = lapses;
    last_missed = missed;
  }
  arrivals.join();
  EXPECT_EQ(f.lapses(clock.load()), 200u);
}

}  // namespace
}  // namespace teleop::transport
