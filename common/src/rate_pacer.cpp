#include "teleop/common/rate_pacer.h"

#include <algorithm>
#include <stdexcept>

namespace teleop {

RatePacer::RatePacer(Clock& clock, int64_t period_ns, uint64_t max_catch_up)
    : clock_(clock), period_ns_(period_ns), max_catch_up_(max_catch_up) {
  if (period_ns <= 0) throw std::invalid_argument("RatePacer: period must be positive");
}

void RatePacer::start() {
  next_deadline_ns_ = clock_.now_ns();
  started_ = true;
}

CycleTick RatePacer::wait_next() {
  if (!started_) start();
  int64_t now = clock_.now_ns();
  if (stats_.cycles > 0 && now > next_deadline_ns_) {
    // the previous cycle's work (or the scheduler) made us miss this deadline
    ++stats_.overruns;
    const int64_t behind = (now - next_deadline_ns_) / period_ns_;
    if (static_cast<uint64_t>(behind) > max_catch_up_) {
      // stalled: drop the missed deadlines instead of bursting through them
      stats_.skipped += static_cast<uint64_t>(behind);
      next_deadline_ns_ += behind * period_ns_;
    }
  }
  while (now < next_deadline_ns_) {
    clock_.sleep_until_ns(next_deadline_ns_);
    now = clock_.now_ns();
  }
  CycleTick tick{stats_.cycles, next_deadline_ns_, now};
  stats_.lateness.record(now - next_deadline_ns_);
  ++stats_.cycles;
  next_deadline_ns_ += period_ns_;
  return tick;
}

void RatePacer::steer_phase(int64_t phase_ns, int64_t max_step_ns) {
  // the phase error in [-period/2, period/2): how far the next deadline lies after the wanted phase
  int64_t error = (next_deadline_ns_ - phase_ns) % period_ns_;
  if (error < 0) error += period_ns_;
  if (error >= period_ns_ / 2) error -= period_ns_;
  next_deadline_ns_ -= std::clamp(error / 8, -max_step_ns, max_step_ns);
}

}  // namespace teleop
