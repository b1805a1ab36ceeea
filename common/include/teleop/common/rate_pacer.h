#pragma once
// Fixed-rate pacing on absolute deadlines of a monotonic clock, with overrun accounting.

#include <cstdint>

#include "teleop/common/clock.h"
#include "teleop/common/histogram.h"

namespace teleop {

/// What the pacer knows about one cycle when it starts.
struct CycleTick {
  uint64_t index = 0;       ///< 0 for the first cycle, +1 per executed cycle
  int64_t deadline_ns = 0;  ///< the absolute time this cycle was due
  int64_t now_ns = 0;       ///< when the pacer released it
};

/// Statistics of a paced loop.
struct PacerStats {
  uint64_t cycles = 0;    ///< cycles released
  uint64_t overruns = 0;  ///< cycles whose work ended after the next deadline
  uint64_t skipped = 0;   ///< deadlines dropped because the loop was too far behind
  DurationHistogram lateness;  ///< release time minus deadline
};

/// Releases one cycle per period at absolute deadlines t0 + k*period, never drifting.
/// A cycle that ends late makes the next one run at once (catching up keeps the average rate);
/// when the loop falls more than `max_catch_up` periods behind (a stall), the missed deadlines
/// are dropped, counted as skipped, and the grid continues from the next future deadline.
/// Real-time safe: no allocation, no locks.
class RatePacer {
 public:
  RatePacer(Clock& clock, int64_t period_ns, uint64_t max_catch_up = 10);

  /// Anchors the grid: the first cycle is due now.
  void start();
  /// Waits for the next deadline and returns the cycle to run.
  CycleTick wait_next();
  /// Moves the grid towards the phase of `phase_ns` (a time the deadlines should fall on, modulo
  /// the period: when a robot that keeps its own cycle delivers its state, plus a margin), by an
  /// eighth of the phase error and at most `max_step_ns` per call: the cycle follows the robot's
  /// clock, its drift included, without a jump in the rate. Real-time safe.
  void steer_phase(int64_t phase_ns, int64_t max_step_ns);

  int64_t period_ns() const { return period_ns_; }
  const PacerStats& stats() const { return stats_; }

 private:
  Clock& clock_;
  int64_t period_ns_;
  uint64_t max_catch_up_;
  int64_t next_deadline_ns_ = 0;
  bool started_ = false;
  PacerStats stats_;
};

}  // namespace teleop
