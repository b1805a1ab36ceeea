#include "hands_off_guard.h"

namespace teleop::leader {

bool HandsOffGuard::update(double speed_mps, int64_t now_ns) {
  if (!off_) {
    if (speed_mps > config_.speed_mps) {
      off_ = true;
      ++events_;
      slow_since_ns_ = -1;
    }
    return off_;
  }
  // slow again: held again once it stayed slow long enough (a hand on it, or at rest)
  if (!(speed_mps < 0.5 * config_.speed_mps)) {
    slow_since_ns_ = -1;
  } else if (slow_since_ns_ < 0) {
    slow_since_ns_ = now_ns;
  } else if (static_cast<double>(now_ns - slow_since_ns_) >= config_.resume_s * 1e9) {
    off_ = false;
  }
  return off_;
}

}  // namespace teleop::leader
