#include "teleop/launcher/summary.h"

#include <spdlog/fmt/fmt.h>

namespace teleop::launcher {

RunSummary summarize(std::vector<runtime::NodeReport> reports) {
  RunSummary summary;
  summary.nodes = std::move(reports);
  for (const auto& receiver : summary.nodes) {
    for (const auto& rx : receiver.received) {
      TopicFlow flow{rx.topic, "?", receiver.name, 0, rx};
      for (const auto& sender : summary.nodes) {
        for (const auto& tx : sender.published) {
          if (tx.topic == rx.topic) {
            flow.from = sender.name;
            flow.sent = tx.sent;
          }
        }
      }
      summary.flows.push_back(flow);
    }
  }
  return summary;
}

std::string format_summary(const RunSummary& summary, const std::string& scenario_name) {
  std::string out = fmt::format("\n== teleop run summary: {} ==\n\n", scenario_name);
  out += fmt::format("{:<10} {:<10} {:>7} {:>8} {:>8} {:>8} {:>9} {:>9} {:>9} {:>11}  {}\n", "node", "state", "run_s",
                     "cycles", "overruns", "skipped", "late_p50", "late_p99", "late_max", "shutdown_ms",
                     "status on bus");
  for (const auto& n : summary.nodes) {
    std::string bus = "none received";
    if (auto it = summary.bus_status.find(n.name); it != summary.bus_status.end()) {
      bus = fmt::format("{} ({} reports)", it->second.state, it->second.reports);
    }
    out += fmt::format("{:<10} {:<10} {:>7.2f} {:>8} {:>8} {:>8} {:>7.0f}us {:>7.0f}us {:>7.0f}us {:>11.1f}  {}\n",
                       n.name, n.final_state, n.run_time_s, n.cycles, n.overruns, n.skipped, n.lateness_p50_ns * 1e-3,
                       n.lateness_p99_ns * 1e-3, n.lateness_max_ns * 1e-3, n.shutdown_ms, bus);
  }
  out += fmt::format("\n{:<30} {:<20} {:>7} {:>7} {:>6} {:>6} {:>8} {:>8} {:>8} {:>8} {:>8}\n", "topic",
                     "direction", "sent", "recv", "lost", "loss%", "rate_Hz", "lat_p50", "lat_p99", "lat_max",
                     "ddl_miss");
  for (const auto& f : summary.flows) {
    const auto& r = f.received;
    const double loss = r.expected ? 100.0 * static_cast<double>(r.lost) / static_cast<double>(r.expected) : 0.0;
    out += fmt::format("{:<30} {:<20} {:>7} {:>7} {:>6} {:>5.2f}% {:>8.1f} {:>6.0f}us {:>6.0f}us {:>6.0f}us {:>8}\n",
                       f.topic, f.from + " -> " + f.to, f.sent, r.received, r.lost, loss, r.rate_hz,
                       r.latency_p50_ns * 1e-3, r.latency_p99_ns * 1e-3, r.latency_max_ns * 1e-3, r.deadline_missed);
  }
  out += "\nlost: sequence gaps between the first and last sample received (discovery time excluded).\n"
         "lat: source stamp to DDS reception (CLOCK_REALTIME), one way. ddl_miss: reader deadline periods "
         "without a sample.\n";
  bool any_counter = false;
  for (const auto& n : summary.nodes) {
    for (const auto& [name, value] : n.counters) {
      if (value == 0) continue;
      if (!any_counter) out += "\nnon-zero counters:\n";
      any_counter = true;
      out += fmt::format("  {}.{} = {}\n", n.name, name, value);
    }
  }
  return out;
}

}  // namespace teleop::launcher
