#include "teleop/runtime/shutdown_signal.h"

#include <unistd.h>
#include <atomic>

#include <csignal>

#include "teleop/common/clock.h"

namespace teleop::runtime {
namespace {

std::atomic<bool> g_requested{false};
std::atomic<int64_t> g_requested_at_ns{0};
std::atomic<bool> g_exit_at_once{false};

// async-signal-safe: write, _exit, clock_gettime and lock-free atomics only
void on_signal(int sig) {
  if (sig != 0 && g_exit_at_once.load()) {
    constexpr char kLine[] = "stopped by a signal before joining the network\n";
    [[maybe_unused]] const ssize_t ignored = write(STDERR_FILENO, kLine, sizeof kLine - 1);
    _exit(128 + sig);
  }
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

void set_signals_exit_at_once(bool at_once) { g_exit_at_once.store(at_once); }

bool shutdown_requested() { return g_requested.load(std::memory_order_relaxed); }

int64_t shutdown_requested_at_ns() { return g_requested_at_ns.load(); }

void request_shutdown() { on_signal(0); }

}  // namespace teleop::runtime
