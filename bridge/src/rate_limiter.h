#pragma once
// At most `max_hz` messages a second on one subscription: a 1 kHz stream thinned to what a viewer
// draws. Slots on a fixed grid of 1/max_hz, a message passing at most one period after its slot, so
// the average is max_hz (not less, as a plain minimum interval between messages would give) and over
// any span T fewer than T * max_hz + 2 pass; after a pause the grid restarts at the next message
// instead of letting a burst through.

#include <cstdint>

namespace teleop::bridge {

class RateLimiter {
 public:
  /// `max_hz` 0: every message passes.
  explicit RateLimiter(double max_hz);

  /// Whether a message arriving at `now_ns` (a monotonic clock) may pass; counts it if so.
  bool admit(int64_t now_ns);

 private:
  int64_t period_ns_;
  int64_t next_ns_ = 0;
  bool started_ = false;
};

}  // namespace teleop::bridge
