#pragma once
// Whether a cycle comes after a stall of its own loop (the process stopped, starved or swapped):
// more time passed since the previous cycle's release than an input may be silent. The release, not
// the deadline: a process stopped while it slept for its next deadline is released late on that
// very deadline (the pacer skips the missed ones only at the cycle after), and its peers must not
// be blamed for the silence its own stop made. What the loop
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
    const bool stalled = released_ && tick.now_ns - last_release_ns_ > threshold_ns_;
    released_ = true;
    last_release_ns_ = tick.now_ns;
    if (stalled) ++stalls_;
    return stalled;
  }
  uint64_t stalls() const { return stalls_; }

 private:
  int64_t threshold_ns_;
  bool released_ = false;
  int64_t last_release_ns_ = 0;
  uint64_t stalls_ = 0;
};

}  // namespace teleop
