#include "teleop/common/clock.h"

#include <time.h>

namespace teleop {
namespace {

int64_t read_clock_ns(clockid_t id) {
  timespec ts{};
  clock_gettime(id, &ts);
  return static_cast<int64_t>(ts.tv_sec) * kNsPerS + ts.tv_nsec;
}

}  // namespace

int64_t monotonic_now_ns() { return read_clock_ns(CLOCK_MONOTONIC); }

int64_t system_now_ns() { return read_clock_ns(CLOCK_REALTIME); }

int64_t MonotonicClock::now_ns() { return monotonic_now_ns(); }

void MonotonicClock::sleep_until_ns(int64_t deadline_ns) {
  timespec ts{};
  ts.tv_sec = deadline_ns / kNsPerS;
  ts.tv_nsec = deadline_ns % kNsPerS;
  // an interrupting signal (EINTR) returns early on purpose: the loop then checks for shutdown
  clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr);
}

}  // namespace teleop
