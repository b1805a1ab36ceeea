#pragma once
// Hands-on detection by speed, for a force-feedback device (docs/devices/plugins.md, "Hands
// off"): an operator's hand does not fling a haptic device; a device let go in contact is pushed
// away by the force rendered on it and speeds up. Faster than `speed_mps` (its flange or handle),
// it counts as let go: the leader fades the feedback out and holds the command (as with the
// dead-man released) until the device has stayed below half that speed for `resume_s`. A
// dead-man button is the better signal where the device has one; this guards those without.

#include <cstdint>
#include <limits>

namespace teleop::leader {

struct HandsOffConfig {
  /// The flange's or handle's speed above which the device counts as let go [m/s]; infinity: off.
  double speed_mps = std::numeric_limits<double>::infinity();
  /// How long it must then stay below half that speed to count as held again [s].
  double resume_s = 0.5;
};

class HandsOffGuard {
 public:
  explicit HandsOffGuard(const HandsOffConfig& config) : config_(config) {}

  /// One cycle: the device's speed now. True while it counts as let go. Real-time safe.
  bool update(double speed_mps, int64_t now_ns);

  bool off() const { return off_; }
  /// Times it counted as let go.
  uint64_t events() const { return events_; }

 private:
  HandsOffConfig config_;
  bool off_ = false;
  int64_t slow_since_ns_ = -1;
  uint64_t events_ = 0;
};

}  // namespace teleop::leader
