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

namespace {

// the impaired links as configured and as they behaved, and what the receivers' loops saw
std::string format_network(const RunSummary& summary) {
  std::string out;
  for (const auto& n : summary.nodes) {
    for (const auto& l : n.links) {
      if (out.empty()) {
        out += fmt::format("\nnetwork impairment (seed {}; per link, as decided by the sender):\n", n.impairment_seed);
        out += fmt::format("{:<20} {:<16} {:>8} {:>8} {:>8} {:>7} {:>7} {:>8} {:>8} {:>6} {:>6} {:>5} {:>5}\n", "link",
                           "profile", "delay", "dly_p50", "dly_p99", "loss", "loss_m", "outage", "burst", "b_max",
                           "dup", "reord", "queue");
      }
      const double measured = l.messages ? static_cast<double>(l.lost) / static_cast<double>(l.messages) : 0.0;
      out += fmt::format("{:<20} {:<16} {:>6.2f}ms {:>6.2f}ms {:>6.2f}ms {:>6.2f}% {:>6.2f}% {:>8} {:>8.2f} {:>6} {:>6} {:>5} {:>5}\n",
                         n.name + " -> " + l.to, l.profile, l.configured_delay_ns * 1e-6, l.delay_p50_ns * 1e-6,
                         l.delay_p99_ns * 1e-6, 100.0 * l.configured_loss, 100.0 * measured, l.outage,
                         l.loss_burst_mean, l.loss_burst_max, l.duplicated, l.reordered, l.queue);
    }
  }
  if (out.empty()) return out;
  out += "delay: configured base delay; dly_p50/p99: delay added (incl. jitter and order keeping); loss: configured "
         "rate, loss_m: measured; burst: mean/max messages lost in a row.\n";
  out += fmt::format("\n{:<30} {:<20} {:>9} {:>9} {:>9} {:>9} {:>9}\n", "application effect", "direction", "age_p50",
                     "age_p99", "age_max", "miss_run", "miss_max");
  for (const auto& f : summary.flows) {
    const auto& r = f.received;
    out += fmt::format("{:<30} {:<20} {:>7.2f}ms {:>7.2f}ms {:>7.2f}ms {:>9.2f} {:>9}\n", f.topic, f.from + " -> " + f.to,
                       r.age_p50_ns * 1e-6, r.age_p99_ns * 1e-6, r.age_max_ns * 1e-6, r.gap_mean, r.gap_max);
  }
  out += "age: how old the newest sample was each time the receiving loop looked; miss_run/miss_max: mean/max "
         "samples missed in a row at the receiver.\n";
  return out;
}

}  // namespace

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
  out += format_network(summary);
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
