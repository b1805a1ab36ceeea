#include "teleop/runtime/shutdown_signal.h"

#include <atomic>
#include <csignal>

#include "teleop/common/clock.h"

namespace teleop::runtime {
namespace {

std::atomic<bool> g_requested{false};
std::atomic<int64_t> g_requested_at_ns{0};

void on_signal(int) {
  // async-signal-safe: clock_gettime and lock-free atomics only
  if (!g_requested.exchange(true)) g_requested_at_ns.store(monotonic_now_ns());
}

}  // namespace

void install_shutdown_handlers() {
  struct sigaction action {};
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  // no SA_RESTART: a sleeping loop wakes up at once (EINTR) and sees the flag
  action.sa_flags = 0;
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

bool shutdown_requested() { return g_requested.load(std::memory_order_relaxed); }

int64_t shutdown_requested_at_ns() { return g_requested_at_ns.load(); }

void request_shutdown() { on_signal(0); }

}  // namespace teleop::runtime
