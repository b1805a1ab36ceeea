#pragma once
// Time sources. The control loops run on CLOCK_MONOTONIC; sample stamps also carry
// CLOCK_REALTIME so that one-way latency can be computed across hosts.

#include <cstdint>

namespace teleop {

constexpr int64_t kNsPerUs = 1'000;
constexpr int64_t kNsPerMs = 1'000'000;
constexpr int64_t kNsPerS = 1'000'000'000;

/// CLOCK_MONOTONIC in ns. Real-time safe.
int64_t monotonic_now_ns();

/// CLOCK_REALTIME in ns since the Unix epoch, plus realtime_offset_ns(). Real-time safe.
int64_t system_now_ns();

/// What this process adds to CLOCK_REALTIME: TELEOP_CLOCK_OFFSET_MS from the environment (read
/// once), else 0. It makes one process a host whose clock is off, to test and show what teleop does
/// with unsynchronised hosts (docs/clocks.md); everything that reads CLOCK_REALTIME (stamps, DDS
/// reception times in transport::Reader) reads it through this.
int64_t realtime_offset_ns();

/// A clock a loop can read and sleep on; abstract so that loop logic is tested with a fake.
class Clock {
 public:
  virtual ~Clock() = default;
  /// Current time in ns on this clock's time base.
  virtual int64_t now_ns() = 0;
  /// Sleeps until the absolute time `deadline_ns` (may return early on a signal).
  virtual void sleep_until_ns(int64_t deadline_ns) = 0;
};

/// CLOCK_MONOTONIC with absolute-deadline sleeps (clock_nanosleep, TIMER_ABSTIME).
class MonotonicClock final : public Clock {
 public:
  int64_t now_ns() override;
  void sleep_until_ns(int64_t deadline_ns) override;
};

}  // namespace teleop
