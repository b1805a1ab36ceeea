#include "teleop/common/clock.h"

#include <time.h>

#include <cstdlib>

namespace teleop {
namespace {

int64_t read_clock_ns(clockid_t id) {
  timespec ts{};
  clock_gettime(id, &ts);
  return static_cast<int64_t>(ts.tv_sec) * kNsPerS + ts.tv_nsec;
}

}  // namespace

int64_t monotonic_now_ns() { return read_clock_ns(CLOCK_MONOTONIC); }

int64_t realtime_offset_ns() {
  static const int64_t offset_ns = [] {
    const char* text = std::getenv("TELEOP_CLOCK_OFFSET_MS");
    return text == nullptr ? int64_t{0} : static_cast<int64_t>(std::strtod(text, nullptr) * 1e6);
  }();
  return offset_ns;
}

int64_t system_now_ns() { return read_clock_ns(CLOCK_REALTIME) + realtime_offset_ns(); }

int64_t MonotonicClock::now_ns() { return monotonic_now_ns(); }

void MonotonicClock::sleep_until_ns(int64_t deadline_ns) {
  timespec ts{};
  ts.tv_sec = deadline_ns / kNsPerS;
  ts.tv_nsec = deadline_ns % kNsPerS;
  // an interrupting signal (EINTR) returns early on purpose: the loop then checks for shutdown
  clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr);
}

}  // namespace teleop
