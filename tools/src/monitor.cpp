#include "teleop/tools/monitor.h"

#include <chrono>
#include <mutex>
#include <thread>

#include "bus.h"
#include "teleop/common/clock.h"
#include "teleop/runtime/shutdown_signal.h"
#include "teleop/tools/monitor_view.h"
#include "teleop/transport/topics.h"

namespace teleop::tools {

int run_monitor(const BusOptions& options, const MonitorOptions& monitor, FILE* out) {
  // before the bus: its reader updates the view until the bus is gone
  std::mutex mutex;
  MonitorView view;
  Bus bus(options, "teleop_monitor");
  auto reader = bus.participant().make_reader(
      transport::topics::kNodeStatus,
      std::function<void(const msg::NodeStatus&, const WriterId&)>([&](const msg::NodeStatus& s, const WriterId& w) {
        std::lock_guard lock(mutex);
        view.update(s, monotonic_now_ns(), w);
      }));
  (void)reader;
  const int64_t start_ns = monotonic_now_ns();
  const int64_t period_ns = static_cast<int64_t>(monitor.refresh_s * 1e9);
  for (int64_t next_ns = start_ns + period_ns; !runtime::shutdown_requested(); next_ns += period_ns) {
    while (!runtime::shutdown_requested() && monotonic_now_ns() < next_ns) {
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    const int64_t now_ns = monotonic_now_ns();
    std::string text;
    {
      std::lock_guard lock(mutex);
      text = monitor.lines ? view.lines(now_ns) : view.table(now_ns, bus.domain_id());
      if (view.nodes() == 0) text = monitor.lines ? "no node yet\n" : "teleop monitor: no node on the bus yet\n";
    }
    // a terminal: clear it and draw from the top left
    if (!monitor.lines) std::fputs("\033[2J\033[H", out);
    std::fputs(text.c_str(), out);
    std::fflush(out);
    if (monitor.duration_s > 0 && now_ns - start_ns >= static_cast<int64_t>(monitor.duration_s * 1e9)) break;
  }
  return 0;
}

}  // namespace teleop::tools
