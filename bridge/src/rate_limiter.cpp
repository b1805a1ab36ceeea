#include "rate_limiter.h"

namespace teleop::bridge {

RateLimiter::RateLimiter(double max_hz) : period_ns_(max_hz > 0 ? static_cast<int64_t>(1e9 / max_hz) : 0) {}

bool RateLimiter::admit(int64_t now_ns) {
  if (period_ns_ == 0) return true;
  if (started_ && now_ns < next_ns_) return false;
  // within a period of its slot the grid holds (the average stays at max_hz); later, it restarts
  const bool on_grid = started_ && now_ns - next_ns_ < period_ns_;
  next_ns_ = (on_grid ? next_ns_ : now_ns) + period_ns_;
  started_ = true;
  return true;
}

}  // namespace teleop::bridge
