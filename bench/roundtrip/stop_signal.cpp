// SIGINT/SIGTERM only set a flag that every loop polls: the pinger unwinds (which stops its
// echo), the echo returns from its loop.

#include <signal.h>

#include <atomic>

#include "roundtrip.h"

namespace teleop::bench {
namespace {

std::atomic<bool> g_stop{false};
static_assert(std::atomic<bool>::is_always_lock_free, "the signal handler needs a lock-free flag");

extern "C" void on_stop_signal(int /*signo*/) { g_stop.store(true); }

}  // namespace

void install_signal_handlers() {
  struct sigaction action {};
  action.sa_handler = on_stop_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = 0;  // no SA_RESTART: blocking calls return EINTR and the loops see the flag
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

bool stop_requested() { return g_stop.load(); }

void throw_if_stopped() {
  if (g_stop.load()) throw Interrupted();
}

}  // namespace teleop::bench
