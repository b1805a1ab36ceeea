// The pinger's loop, common to every variant: sends on absolute deadlines and accounts the
// measured window (pacer, CPU time of both processes).

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <stdexcept>

#include "pinger.h"
#include "profile_window.h"
#include "teleop/common/clock.h"
#include "teleop/common/rate_pacer.h"

namespace teleop::bench {
namespace {

/// Sends until at least opt.warmup samples went out and a first reply came back; returns the
/// last sequence number sent. Starts the pacer.
uint64_t warm_up(const Options& opt, const RttRecorder& rec, EchoProcess& echo, RatePacer& pacer, const SendFn& send) {
  const int64_t reply_deadline = monotonic_now_ns() + static_cast<int64_t>(opt.timeout_s * 1e9);
  uint64_t seq = 0;
  pacer.start();
  while (true) {
    throw_if_stopped();
    const auto tick = pacer.wait_next();
    send(++seq);
    if (seq >= opt.warmup && rec.replies() > 0) return seq;
    if (tick.now_ns > reply_deadline) {
      echo.check_alive();
      throw std::runtime_error("the echo matched but no reply came back within " + seconds_text(opt.timeout_s) + " s");
    }
    if (seq % 256 == 0) echo.check_alive();
  }
}

/// Sends the opt.samples measured samples after `seq`, recording the pacer's figures and the CPU
/// time both processes spent meanwhile.
void measure(const Options& opt, EchoProcess& echo, RatePacer& pacer, uint64_t seq, const SendFn& send,
             VariantResult& result) {
  const uint64_t overruns0 = pacer.stats().overruns;
  const uint64_t skipped0 = pacer.stats().skipped;
  const int64_t ping_cpu0 = own_cpu_ns();
  const int64_t echo_cpu0 = echo.cpu_ns();
  profile_window_open();
  for (uint64_t i = 0; i < opt.samples; ++i) {
    throw_if_stopped();
    const auto tick = pacer.wait_next();
    result.lateness.record(tick.now_ns - tick.deadline_ns);
    if (!send(++seq)) ++result.send_failed;
    ++result.sent;
  }
  profile_window_close();
  result.cpu_ping_ns = own_cpu_ns() - ping_cpu0;
  const int64_t echo_cpu1 = echo.cpu_ns();
  result.cpu_echo_ns = echo_cpu0 < 0 || echo_cpu1 < 0 ? -1 : echo_cpu1 - echo_cpu0;
  result.overruns = pacer.stats().overruns - overruns0;
  result.skipped = pacer.stats().skipped - skipped0;
}

}  // namespace

std::string seconds_text(double s) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", s);
  return buf;
}

void run_paced(const Options& opt, RttRecorder& rec, EchoProcess& echo, const SendFn& send, VariantResult& result) {
  result.topics = static_cast<int>(rec.topics());
  MonotonicClock clock;
  const auto period_ns = static_cast<int64_t>(1e9 / opt.rate_hz);
  RatePacer pacer(clock, period_ns);
  const uint64_t first = warm_up(opt, rec, echo, pacer, send) + 1;
  rec.open_window(first);
  result.window_begin = first;
  measure(opt, echo, pacer, first - 1, send, result);
  // grace: the last replies are still on their way
  const int64_t grace_end = monotonic_now_ns() + std::max<int64_t>(500 * kNsPerMs, 3 * period_ns);
  const uint64_t expected = result.sent * rec.topics();
  while (rec.received() < expected && monotonic_now_ns() < grace_end && !stop_requested()) usleep(1'000);
  result.rtt = rec.snapshot();
  echo.check_alive();  // an echo that died mid-run explains the losses: say so
}

}  // namespace teleop::bench
