#include "teleop/common/rate_pacer.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <vector>

namespace teleop {
namespace {

// Simulated time: sleeping jumps to the deadline, work is simulated by advancing the time.
class FakeClock final : public Clock {
 public:
  explicit FakeClock(int64_t start_ns) : now_(start_ns) {}
  int64_t now_ns() override { return now_; }
  void sleep_until_ns(int64_t deadline_ns) override {
    ++sleeps_;
    if (deadline_ns > now_) now_ = deadline_ns;
  }
  /// Simulates work (or a stall) taking `ns`.
  void advance(int64_t ns) { now_ += ns; }
  int sleeps() const { return sleeps_; }

 private:
  int64_t now_;
  int sleeps_ = 0;
};

constexpr int64_t kT0 = 5'000'000'000;  // arbitrary, non-zero start
constexpr int64_t kPeriod = 1'000'000;   // 1 kHz

TEST(RatePacer, RejectsNonPositivePeriodWhenConstructed) {
  FakeClock clock(kT0);
  EXPECT_THROW(RatePacer(clock, 0), std::invalid_argument);
  EXPECT_THROW(RatePacer(clock, -5), std::invalid_argument);
}

TEST(RatePacer, ReleasesFirstCycleImmediatelyAtStart) {
  FakeClock clock(kT0);
  RatePacer pacer(clock, kPeriod);
  pacer.start();
  const CycleTick tick = pacer.wait_next();
  EXPECT_EQ(tick.index, 0u);
  EXPECT_EQ(tick.deadline_ns, kT0);
  EXPECT_EQ(tick.now_ns, kT0);
  EXPECT_EQ(clock.now_ns(), kT0);
  EXPECT_EQ(pacer.stats().cycles, 1u);
}

TEST(RatePacer, StartsImplicitlyOnFirstWaitWhenNotStarted) {
  FakeClock clock(kT0);
  RatePacer pacer(clock, kPeriod);
  EXPECT_EQ(pacer.wait_next().deadline_ns, kT0);
  EXPECT_EQ(pacer.wait_next().deadline_ns, kT0 + kPeriod);
}

TEST(RatePacer, KeepsDeadlinesOnTheGridWithoutDriftWhenWorkVaries) {
  FakeClock clock(kT0);
  RatePacer pacer(clock, kPeriod);
  pacer.start();
  constexpr uint64_t kCycles = 10'000;
  for (uint64_t k = 0; k < kCycles; ++k) {
    const CycleTick tick = pacer.wait_next();
    ASSERT_EQ(tick.index, k);
    ASSERT_EQ(tick.deadline_ns, kT0 + static_cast<int64_t>(k) * kPeriod) << "cycle " << k;
    ASSERT_EQ(tick.now_ns, tick.deadline_ns) << "cycle " << k;
    // work of varying length, always shorter than a period: a relative sleep would drift
    clock.advance(static_cast<int64_t>((k * 37) % 900) * 1000 + 1);
  }
  const PacerStats& s = pacer.stats();
  EXPECT_EQ(s.cycles, kCycles);
  EXPECT_EQ(s.overruns, 0u);
  EXPECT_EQ(s.skipped, 0u);
  EXPECT_EQ(s.lateness.count(), kCycles);
  EXPECT_EQ(s.lateness.max_ns(), 0);
}

TEST(RatePacer, CountsOverrunAndReleasesNextCycleImmediatelyWhenWorkExceedsPeriod) {
  FakeClock clock(kT0);
  RatePacer pacer(clock, kPeriod);
  pacer.start();
  EXPECT_EQ(pacer.wait_next().deadline_ns, kT0);
  clock.advance(kPeriod + kPeriod / 2);  // work took 1.5 periods
  const int sleeps_before = clock.sleeps();

  const CycleTick late = pacer.wait_next();
  EXPECT_EQ(late.index, 1u);
  EXPECT_EQ(late.deadline_ns, kT0 + kPeriod);
  EXPECT_EQ(late.now_ns, kT0 + kPeriod + kPeriod / 2);  // released at once, no sleep
  EXPECT_EQ(clock.sleeps(), sleeps_before);
  EXPECT_EQ(pacer.stats().overruns, 1u);
  EXPECT_EQ(pacer.stats().skipped, 0u);
  EXPECT_EQ(pacer.stats().lateness.max_ns(), kPeriod / 2);

  // catch-up done: the following cycle waits for its own deadline on the original grid
  const CycleTick next = pacer.wait_next();
  EXPECT_EQ(next.deadline_ns, kT0 + 2 * kPeriod);
  EXPECT_EQ(next.now_ns, kT0 + 2 * kPeriod);
  EXPECT_EQ(pacer.stats().overruns, 1u);
  EXPECT_EQ(pacer.stats().cycles, 3u);
}

TEST(RatePacer, CatchesUpBackToBackWhenBehindByLessThanMaxCatchUp) {
  FakeClock clock(kT0);
  RatePacer pacer(clock, kPeriod, /*max_catch_up=*/10);
  pacer.start();
  (void)pacer.wait_next();
  clock.advance(5 * kPeriod + 100);  // behind by 5 periods: catch up, do not skip
  const int64_t stalled_until = clock.now_ns();
  for (int64_t k = 1; k <= 5; ++k) {
    const CycleTick tick = pacer.wait_next();
    EXPECT_EQ(tick.deadline_ns, kT0 + k * kPeriod);
    EXPECT_EQ(tick.now_ns, stalled_until) << "cycle " << k << " must run at once";
  }
  const CycleTick back = pacer.wait_next();
  EXPECT_EQ(back.deadline_ns, kT0 + 6 * kPeriod);
  EXPECT_EQ(back.now_ns, kT0 + 6 * kPeriod);  // on the grid again
  EXPECT_EQ(pacer.stats().skipped, 0u);
  EXPECT_EQ(pacer.stats().overruns, 5u);      // each catch-up cycle started late
  EXPECT_EQ(pacer.stats().cycles, 7u);
  EXPECT_EQ(pacer.stats().lateness.max_ns(), 4 * kPeriod + 100);
}

TEST(RatePacer, SkipsMissedDeadlinesAndKeepsGridPhaseWhenStalledBeyondMaxCatchUp) {
  FakeClock clock(kT0);
  constexpr uint64_t kMaxCatchUp = 10;
  RatePacer pacer(clock, kPeriod, kMaxCatchUp);
  pacer.start();
  for (int k = 0; k < 3; ++k) (void)pacer.wait_next();  // cycles 0..2; next due t0 + 3P
  clock.advance(kPeriod / 4);                             // now t0 + 2.25P
  clock.advance(50 * kPeriod);                            // a stall: now t0 + 52.25P

  const CycleTick resumed = pacer.wait_next();
  // 49 whole periods behind deadline t0+3P: 49 deadlines dropped, the cycle due at t0+52P runs
  EXPECT_EQ(pacer.stats().skipped, 49u);
  EXPECT_EQ(pacer.stats().overruns, 1u);
  EXPECT_EQ(resumed.index, 3u);
  EXPECT_EQ(resumed.deadline_ns, kT0 + 52 * kPeriod);
  EXPECT_EQ(resumed.now_ns, kT0 + 52 * kPeriod + kPeriod / 4);
  // no burst: the next cycle waits for the next grid point, so the phase is kept
  for (int64_t k = 53; k < 60; ++k) {
    const CycleTick tick = pacer.wait_next();
    EXPECT_EQ(tick.deadline_ns, kT0 + k * kPeriod);
    EXPECT_EQ(tick.now_ns, tick.deadline_ns);
    EXPECT_EQ((tick.deadline_ns - kT0) % kPeriod, 0);
  }
  EXPECT_EQ(pacer.stats().skipped, 49u);
  EXPECT_EQ(pacer.stats().overruns, 1u);
}

TEST(RatePacer, CatchesUpWithoutSkippingWhenBehindExactlyMaxCatchUp) {
  FakeClock clock(kT0);
  RatePacer pacer(clock, kPeriod, /*max_catch_up=*/3);
  pacer.start();
  (void)pacer.wait_next();             // next due t0 + P
  clock.advance(4 * kPeriod);          // now t0 + 4P: 3 whole periods behind, not more
  EXPECT_EQ(pacer.wait_next().deadline_ns, kT0 + kPeriod);
  EXPECT_EQ(pacer.stats().skipped, 0u);
}

TEST(RatePacer, SkipsWhenMaxCatchUpIsZeroAndAFullPeriodIsMissed) {
  FakeClock clock(kT0);
  RatePacer pacer(clock, kPeriod, /*max_catch_up=*/0);
  pacer.start();
  (void)pacer.wait_next();                 // next due t0 + P
  clock.advance(2 * kPeriod + 10);         // now t0 + 2P + 10: 1 period behind
  const CycleTick tick = pacer.wait_next();
  EXPECT_EQ(pacer.stats().skipped, 1u);
  EXPECT_EQ(tick.deadline_ns, kT0 + 2 * kPeriod);
  EXPECT_EQ(tick.now_ns, kT0 + 2 * kPeriod + 10);
}

TEST(RatePacer, RecordsLatenessOfEachReleaseWhenTheClockWakesLate) {
  // a clock that oversleeps by a fixed amount, like a real scheduler
  class LateClock final : public Clock {
   public:
    int64_t now_ns() override { return now; }
    void sleep_until_ns(int64_t deadline_ns) override { now = deadline_ns + 7'000; }
    int64_t now = kT0;
  } clock;
  RatePacer pacer(clock, kPeriod);
  pacer.start();
  EXPECT_EQ(pacer.wait_next().now_ns, kT0);  // first cycle: on time
  for (int k = 1; k <= 100; ++k) {
    const CycleTick tick = pacer.wait_next();
    EXPECT_EQ(tick.deadline_ns, kT0 + k * kPeriod);
    EXPECT_EQ(tick.now_ns - tick.deadline_ns, 7'000);
  }
  const DurationHistogram& lateness = pacer.stats().lateness;
  EXPECT_EQ(lateness.count(), 101u);
  EXPECT_EQ(lateness.min_ns(), 0);
  EXPECT_EQ(lateness.max_ns(), 7'000);
  EXPECT_EQ(lateness.percentile_ns(0.5), 7'000);
  EXPECT_EQ(pacer.stats().overruns, 0u);  // waking late is not an overrun of the work
}

TEST(RatePacer, SleepsAgainWhenTheClockWakesEarly) {
  // a sleep interrupted by a signal returns early; the pacer must not release before the deadline
  class EarlyClock final : public Clock {
   public:
    int64_t now_ns() override { return now; }
    void sleep_until_ns(int64_t deadline_ns) override {
      ++sleeps;
      now = (deadline_ns - now > 10) ? now + (deadline_ns - now) / 2 : deadline_ns;
    }
    int64_t now = kT0;
    int sleeps = 0;
  } clock;
  RatePacer pacer(clock, kPeriod);
  pacer.start();
  (void)pacer.wait_next();
  const CycleTick tick = pacer.wait_next();
  EXPECT_EQ(tick.deadline_ns, kT0 + kPeriod);
  EXPECT_GE(tick.now_ns, tick.deadline_ns);
  EXPECT_GT(clock.sleeps, 1);
}

// A robot whose 1 kHz cycle runs 0.4 ms off the pacer's and 50 ppm fast: its states arrive at
// t_robot(k) + 0.3 ms. Steered towards arrival + 0.15 ms, the deadlines reach that phase and stay
// on it, moving at most 25 us per cycle, without an overrun or a skipped deadline.
TEST(RatePacer, SteersItsPhaseOntoARobotsCycleAndFollowsItsDrift) {
  FakeClock clock(kT0);
  RatePacer pacer(clock, kPeriod);
  pacer.start();
  const auto robot_cycle = [](int64_t k) { return kT0 + 400'000 + k * (kPeriod - 50); };
  int64_t previous_deadline = 0;
  int64_t phase_error = 0;
  for (int64_t k = 0; k < 4000; ++k) {
    const CycleTick tick = pacer.wait_next();
    if (k > 0) {
      EXPECT_LE(std::abs(tick.deadline_ns - previous_deadline - kPeriod), 25'000) << "cycle " << k;
    }
    previous_deadline = tick.deadline_ns;
    // the newest state that has arrived by now
    int64_t newest = (tick.now_ns - robot_cycle(0) - 300'000) / (kPeriod - 50);
    const int64_t arrival = robot_cycle(newest) + 300'000;
    phase_error = tick.deadline_ns - (arrival + 150'000);
    clock.advance(100'000);
    pacer.steer_phase(arrival + 150'000, kPeriod / 40);
  }
  // the last error: how far the deadline lags the drifting phase, within the step's resolution
  EXPECT_LT(std::abs(phase_error), 1'000) << phase_error;
  EXPECT_EQ(pacer.stats().overruns, 0u);
  EXPECT_EQ(pacer.stats().skipped, 0u);
}

// the error is taken to the nearest deadline of the phase: half a period early, never a whole one late
TEST(RatePacer, SteersThroughTheShorterWayRoundThePeriod) {
  FakeClock clock(kT0);
  RatePacer pacer(clock, kPeriod);
  pacer.start();
  (void)pacer.wait_next();  // the next deadline is kT0 + kPeriod
  // 0.9 ms after it: modulo the period, 0.1 ms before it
  pacer.steer_phase(kT0 + kPeriod + 900'000, 25'000);
  EXPECT_EQ(pacer.wait_next().deadline_ns, kT0 + kPeriod - 12'500);  // an eighth of 0.1 ms earlier
  // 0.3875 ms before the next deadline: an eighth is more than the cap
  pacer.steer_phase(kT0 + 2 * kPeriod - 400'000, 25'000);
  EXPECT_EQ(pacer.wait_next().deadline_ns, kT0 + 2 * kPeriod - 12'500 - 25'000);
}

}  // namespace
}  // namespace teleop
