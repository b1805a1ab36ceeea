#include "teleop/tools/monitor_view.h"

#include <spdlog/fmt/fmt.h>

#include <cmath>
#include <ctime>

#include "teleop/runtime/status_names.h"

namespace teleop::tools {
namespace {

std::string faults_text(const msg::NodeStatus& s) {
  std::string text;
  for (uint32_t f : s.fault_codes()) text += (text.empty() ? "" : ",") + std::string(runtime::fault_name(f));
  return text.empty() ? "-" : text;
}

// the loop rate between the two newest statuses, by the node's own clock
double measured_rate_hz(const msg::NodeStatus& prev, const msg::NodeStatus& last) {
  const double dt_s = static_cast<double>(last.header().stamp_mono_ns() - prev.header().stamp_mono_ns()) * 1e-9;
  if (dt_s <= 0 || last.loop().cycles() < prev.loop().cycles()) return NAN;
  return static_cast<double>(last.loop().cycles() - prev.loop().cycles()) / dt_s;
}

// the share of samples lost between the two newest statuses (the whole run before a second one)
double loss_percent(uint64_t received, uint64_t lost, uint64_t received_before, uint64_t lost_before) {
  if (received < received_before || lost < lost_before) return NAN;  // a restarted node
  const double r = static_cast<double>(received - received_before);
  const double l = static_cast<double>(lost - lost_before);
  return r + l > 0 ? 100.0 * l / (r + l) : NAN;
}

const msg::FlowStatus* flow_named(const msg::NodeStatus& s, const std::string& topic) {
  for (const auto& f : s.flows()) {
    if (topic == f.topic().c_str()) return &f;
  }
  return nullptr;
}

const msg::LinkStatistics* link_to(const msg::NodeStatus& s, const std::string& peer) {
  for (const auto& l : s.links()) {
    if (peer == l.peer().c_str()) return &l;
  }
  return nullptr;
}

std::string ms(double ns) { return std::isfinite(ns) && ns >= 0 ? fmt::format("{:.2f} ms", ns * 1e-6) : "-"; }
std::string pct(double p) { return std::isfinite(p) ? fmt::format("{:.1f} %", p) : "-"; }

struct FlowNumbers {
  std::string topic;
  bool awaited;
  int writers;
  std::string age, latency, loss;
  std::string authority;  // whom it follows, what it refused
};

// ", its clock 2000.1 ms ahead" where the followed writer's samples say its clock (or the fastest
// path from it) is more than 10 ms away from the node's (common/clock_offset.h); "" otherwise
std::string clock_text(const msg::FlowStatus& f) {
  const double offset_ms = static_cast<double>(f.clock_offset_ns()) * 1e-6;
  if (std::abs(offset_ms) <= 10.0) return "";
  return fmt::format(", its clock {:.1f} ms {}", std::abs(offset_ms), offset_ms < 0 ? "ahead" : "behind or slow");
}

// "following leader, refused 1234 (rogue: other_writer)"; "" when it follows no one yet
std::string authority_text(const msg::FlowStatus& f) {
  if (f.following().size() == 0) return "";
  std::string text = fmt::format("following {}{}{}", f.following().c_str(), f.in_force() ? "" : " (NOT IN FORCE)",
                                 clock_text(f));
  const uint64_t refused =
      f.refused_other_writer() + f.refused_not_accepted() + f.refused_sequence_jump() + f.refused_invalid();
  if (refused == 0) return text;
  std::string why = runtime::refusal_name(f.refusal());
  if (f.refusal_detail().size() > 0) why += std::string(" ") + f.refusal_detail().c_str();
  return text + fmt::format(", refused {} (last: {} {})", refused, f.refused_source().c_str(), why);
}

FlowNumbers flow_numbers(const msg::FlowStatus& f, const msg::FlowStatus* before) {
  const double loss = before ? loss_percent(f.received(), f.lost(), before->received(), before->lost())
                             : loss_percent(f.received(), f.lost(), 0, 0);
  return {f.topic().c_str(),
          f.awaited(),
          f.writers(),
          f.age_ns() < 0 ? "never" : ms(static_cast<double>(f.age_ns())),
          f.received() > 0 ? ms(static_cast<double>(f.latency_ns())) : "-",
          pct(loss),
          authority_text(f)};
}

struct LinkNumbers {
  std::string peer, profile, delay_p50, delay_p99, loss;
};

LinkNumbers link_numbers(const msg::LinkStatistics& l, const msg::LinkStatistics* before) {
  const uint64_t m0 = before ? before->messages() : 0,
                 lost0 = before ? before->lost() + before->outage() + before->queue() : 0;
  const uint64_t lost = l.lost() + l.outage() + l.queue();
  const double sent = static_cast<double>(l.messages()) - static_cast<double>(m0);
  const double dropped = static_cast<double>(lost) - static_cast<double>(lost0);
  return {l.peer().c_str(), l.profile().c_str(), ms(static_cast<double>(l.delay_p50_ns())),
          ms(static_cast<double>(l.delay_p99_ns())), pct(sent > 0 ? 100.0 * dropped / sent : NAN)};
}

}  // namespace

void MonitorView::update(const msg::NodeStatus& status, int64_t now_ns, const WriterId& writer) {
  Node& node = nodes_[status.header().source().c_str()];
  const auto heard = node.writers.find(writer.bytes);
  const bool back = node.seen && writer.bytes != node.last_writer && heard != node.writers.end() &&
                    now_ns - heard->second <= silent_after_ns_;
  if (back) node.clash_until_ns = now_ns + silent_after_ns_;
  node.writers[writer.bytes] = now_ns;
  node.last_writer = writer.bytes;
  if (node.seen) {
    node.previous = node.last;
    node.has_previous = true;
  }
  node.seen = true;
  node.last = status;
  node.received_ns = now_ns;
}

size_t MonitorView::live_writers(const Node& node, int64_t now_ns) const {
  size_t n = 0;
  for (const auto& [writer, seen_ns] : node.writers) n += now_ns - seen_ns <= silent_after_ns_ ? 1 : 0;
  return n;
}

std::string MonitorView::state_text(const Node& node, int64_t now_ns) const {
  // two nodes with one name (two setups on one domain): their statuses alternate under it
  if (now_ns < node.clash_until_ns) return fmt::format("DUPLICATE NAME ({} nodes)", live_writers(node, now_ns));
  const int64_t silent_ns = now_ns - node.received_ns;
  if (silent_ns > silent_after_ns_ && node.last.state() != msg::STATE_STOPPING) {
    return fmt::format("SILENT {:.1f} s (was {})", silent_ns * 1e-9, runtime::state_name(node.last.state()));
  }
  return runtime::state_name(node.last.state());
}

std::string MonitorView::table(int64_t now_ns, int domain_id) const {
  const std::time_t wall = std::time(nullptr);
  char clock[16];
  std::strftime(clock, sizeof(clock), "%H:%M:%S", std::localtime(&wall));
  std::string text = fmt::format("teleop monitor  domain {}  {} node{}  {}\n\n", domain_id, nodes_.size(),
                                 nodes_.size() == 1 ? "" : "s", clock);
  text += fmt::format("{:<14} {:<9} {:<26} {:<24} {:>9} {:>8} {:>7} {:>10} {:>9} {}\n", "NODE", "ROLE", "STATE",
                      "FAULTS", "RATE Hz", "OVERRUN", "SKIP", "LATE p99", "TDPA J", "CAN");
  for (const auto& [name, node] : nodes_) {
    const msg::NodeStatus& s = node.last;
    const double rate = node.has_previous ? measured_rate_hz(node.previous, s) : NAN;
    text += fmt::format("{:<14} {:<9} {:<26} {:<24} {:>9} {:>8} {:>7} {:>10} {:>9} {}\n", name,
                        runtime::role_name(s.role()), state_text(node, now_ns), faults_text(s),
                        std::isfinite(rate) ? fmt::format("{:.1f}", rate) : "-", s.loop().overruns(),
                        s.loop().skipped(), ms(static_cast<double>(s.loop().lateness_p99_ns())),
                        std::isfinite(s.tdpa_energy_j()) ? fmt::format("{:.3f}", s.tdpa_energy_j()) : "-",
                        s.can_bus_state().size() > 0 ? s.can_bus_state().c_str() : "-");
    for (const auto& f : s.flows()) {
      const FlowNumbers n = flow_numbers(f, node.has_previous ? flow_named(node.previous, f.topic().c_str()) : nullptr);
      text += fmt::format("   <- {:<34} {}  age {}  latency {}  loss {}{}\n", n.topic,
                          n.writers > 0 ? fmt::format("{} writer{}", n.writers, n.writers == 1 ? "" : "s")
                          : n.awaited   ? std::string("WAITING FOR A WRITER")
                                        : std::string("no writer (optional)"),
                          n.age, n.latency, n.loss, n.authority.empty() ? "" : "  " + n.authority);
    }
    for (const auto& l : s.links()) {
      const LinkNumbers n = link_numbers(l, node.has_previous ? link_to(node.previous, l.peer().c_str()) : nullptr);
      text += fmt::format("   -> {:<14} profile {:<12} added delay p50 {} p99 {}  dropped {}\n", n.peer, n.profile,
                          n.delay_p50, n.delay_p99, n.loss);
    }
  }
  return text;
}

std::string MonitorView::lines(int64_t now_ns) const {
  std::string text;
  for (const auto& [name, node] : nodes_) {
    const msg::NodeStatus& s = node.last;
    const double rate = node.has_previous ? measured_rate_hz(node.previous, s) : NAN;
    text += fmt::format("node={} role={} state={} faults={} rate_hz={} overruns={} skipped={} lateness_p99={}", name,
                        runtime::role_name(s.role()), state_text(node, now_ns), faults_text(s),
                        std::isfinite(rate) ? fmt::format("{:.1f}", rate) : "-", s.loop().overruns(),
                        s.loop().skipped(), ms(static_cast<double>(s.loop().lateness_p99_ns())));
    if (std::isfinite(s.tdpa_energy_j())) text += fmt::format(" tdpa_j={:.3f}", s.tdpa_energy_j());
    if (s.can_bus_state().size() > 0) text += fmt::format(" can={}", s.can_bus_state().c_str());
    for (const auto& f : s.flows()) {
      const FlowNumbers n = flow_numbers(f, node.has_previous ? flow_named(node.previous, f.topic().c_str()) : nullptr);
      text += fmt::format(" flow[{} writers={}{} age={} latency={} loss={}{}]", n.topic, n.writers,
                          n.awaited ? "" : " optional", n.age, n.latency, n.loss,
                          n.authority.empty() ? "" : " " + n.authority);
    }
    for (const auto& l : s.links()) {
      const LinkNumbers n = link_numbers(l, node.has_previous ? link_to(node.previous, l.peer().c_str()) : nullptr);
      text += fmt::format(" link[{} profile={} delay_p50={} dropped={}]", n.peer, n.profile, n.delay_p50, n.loss);
    }
    text += "\n";
  }
  return text;
}

}  // namespace teleop::tools
