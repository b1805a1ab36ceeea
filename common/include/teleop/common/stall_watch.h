#pragma once
// Whether a cycle comes after a stall of its own loop (the process stopped, starved or swapped):
// more time passed since the previous cycle's deadline than an input may be silent. What the loop
// drains then is a backlog, and its newest sample must not act as a step: nodes treat such a
// cycle as a hold and rejoin from the held pose, as after a lost peer.

#include <cstdint>

#include "teleop/common/rate_pacer.h"

namespace teleop {

class StallWatch {
 public:
  explicit StallWatch(int64_t threshold_ns) : threshold_ns_(threshold_ns) {}

  /// Once per cycle. Real-time safe.
  bool stalled(const CycleTick& tick) {
    const bool stalled = last_deadline_ns_ != 0 && tick.deadline_ns - last_deadline_ns_ > threshold_ns_;
    last_deadline_ns_ = tick.deadline_ns;
    if (stalled) ++stalls_;
    return stalled;
  }
  uint64_t stalls() const { return stalls_; }

 private:
  int64_t threshold_ns_;
  int64_t last_deadline_ns_ = 0;
  uint64_t stalls_ = 0;
};

}  // namespace teleop
