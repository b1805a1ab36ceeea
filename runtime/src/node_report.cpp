#include "teleop/runtime/node_report.h"

#include <yaml-cpp/yaml.h>

#include <fstream>
#include <stdexcept>

#include "teleop/common/config.h"

namespace teleop::runtime {

void NodeReport::add_loop(const PacerStats& stats) {
  cycles = stats.cycles;
  overruns = stats.overruns;
  skipped = stats.skipped;
  lateness_p50_ns = stats.lateness.percentile_ns(0.50);
  lateness_p99_ns = stats.lateness.percentile_ns(0.99);
  lateness_max_ns = stats.lateness.max_ns();
}

void NodeReport::add_links(const transport::Participant& participant) {
  const auto* engine = participant.impairment();
  if (engine == nullptr) return;
  impairment_seed = engine->seed();
  for (const auto& l : engine->reports()) {
    ImpairedLink link;
    link.to = l.to;
    link.profile = l.profile;
    link.messages = l.stats.messages;
    link.delivered = l.stats.delivered;
    link.lost = l.stats.lost;
    link.outage = l.stats.outage;
    link.queue = l.stats.queue;
    link.duplicated = l.stats.duplicated;
    link.reordered = l.stats.reordered;
    link.loss_burst_mean = l.stats.loss_runs.mean_ns();
    link.loss_burst_max = static_cast<uint64_t>(l.stats.loss_runs.max_ns());
    link.delay_p50_ns = l.stats.delay.percentile_ns(0.5);
    link.delay_p99_ns = l.stats.delay.percentile_ns(0.99);
    link.delay_max_ns = l.stats.delay.max_ns();
    link.configured_loss = l.configured_loss;
    link.configured_delay_ns = l.configured_delay_ns;
    links.push_back(link);
  }
}

ReceivedTopic NodeReport::received_from(const std::string& topic, const SequenceTracker& stats,
                                        const DurationHistogram& age, uint64_t deadline_missed,
                                        uint64_t liveliness_lost) {
  ReceivedTopic r;
  r.topic = topic;
  r.received = stats.received();
  r.expected = stats.expected();
  r.lost = stats.lost();
  r.duplicates = stats.duplicates();
  r.reordered = stats.reordered();
  r.first_seq = stats.first_seq();
  r.last_seq = stats.last_seq();
  r.rate_hz = stats.rate_hz();
  r.latency_p50_ns = stats.latency().percentile_ns(0.50);
  r.latency_p99_ns = stats.latency().percentile_ns(0.99);
  r.latency_max_ns = stats.latency().max_ns();
  r.deadline_missed = deadline_missed;
  r.liveliness_lost = liveliness_lost;
  r.gap_max = static_cast<uint64_t>(stats.gaps().max_ns());
  r.gap_mean = stats.gaps().mean_ns();
  r.age_p50_ns = age.percentile_ns(0.50);
  r.age_p99_ns = age.percentile_ns(0.99);
  r.age_max_ns = age.max_ns();
  return r;
}

void write_report(const NodeReport& report, const std::string& path) {
  YAML::Emitter out;
  out << YAML::BeginMap;
  out << YAML::Key << "name" << YAML::Value << report.name;
  out << YAML::Key << "role" << YAML::Value << report.role;
  out << YAML::Key << "final_state" << YAML::Value << report.final_state;
  out << YAML::Key << "rate_hz" << YAML::Value << report.rate_hz;
  out << YAML::Key << "run_time_s" << YAML::Value << report.run_time_s;
  out << YAML::Key << "cycles" << YAML::Value << report.cycles;
  out << YAML::Key << "overruns" << YAML::Value << report.overruns;
  out << YAML::Key << "skipped" << YAML::Value << report.skipped;
  out << YAML::Key << "lateness_p50_ns" << YAML::Value << report.lateness_p50_ns;
  out << YAML::Key << "lateness_p99_ns" << YAML::Value << report.lateness_p99_ns;
  out << YAML::Key << "lateness_max_ns" << YAML::Value << report.lateness_max_ns;
  out << YAML::Key << "shutdown_ms" << YAML::Value << report.shutdown_ms;
  out << YAML::Key << "published" << YAML::Value << YAML::BeginSeq;
  for (const auto& p : report.published) {
    out << YAML::Flow << YAML::BeginMap << YAML::Key << "topic" << YAML::Value << p.topic << YAML::Key << "sent"
        << YAML::Value << p.sent << YAML::Key << "failed" << YAML::Value << p.failed << YAML::EndMap;
  }
  out << YAML::EndSeq;
  out << YAML::Key << "received" << YAML::Value << YAML::BeginSeq;
  for (const auto& r : report.received) {
    out << YAML::BeginMap;
    out << YAML::Key << "topic" << YAML::Value << r.topic;
    out << YAML::Key << "received" << YAML::Value << r.received;
    out << YAML::Key << "expected" << YAML::Value << r.expected;
    out << YAML::Key << "lost" << YAML::Value << r.lost;
    out << YAML::Key << "duplicates" << YAML::Value << r.duplicates;
    out << YAML::Key << "reordered" << YAML::Value << r.reordered;
    out << YAML::Key << "first_seq" << YAML::Value << r.first_seq;
    out << YAML::Key << "last_seq" << YAML::Value << r.last_seq;
    out << YAML::Key << "rate_hz" << YAML::Value << r.rate_hz;
    out << YAML::Key << "latency_p50_ns" << YAML::Value << r.latency_p50_ns;
    out << YAML::Key << "latency_p99_ns" << YAML::Value << r.latency_p99_ns;
    out << YAML::Key << "latency_max_ns" << YAML::Value << r.latency_max_ns;
    out << YAML::Key << "deadline_missed" << YAML::Value << r.deadline_missed;
    out << YAML::Key << "liveliness_lost" << YAML::Value << r.liveliness_lost;
    out << YAML::Key << "gap_max" << YAML::Value << r.gap_max;
    out << YAML::Key << "gap_mean" << YAML::Value << r.gap_mean;
    out << YAML::Key << "age_p50_ns" << YAML::Value << r.age_p50_ns;
    out << YAML::Key << "age_p99_ns" << YAML::Value << r.age_p99_ns;
    out << YAML::Key << "age_max_ns" << YAML::Value << r.age_max_ns;
    out << YAML::EndMap;
  }
  out << YAML::EndSeq;
  out << YAML::Key << "impairment_seed" << YAML::Value << report.impairment_seed;
  out << YAML::Key << "links" << YAML::Value << YAML::BeginSeq;
  for (const auto& l : report.links) {
    out << YAML::BeginMap;
    out << YAML::Key << "to" << YAML::Value << l.to;
    out << YAML::Key << "profile" << YAML::Value << l.profile;
    out << YAML::Key << "messages" << YAML::Value << l.messages;
    out << YAML::Key << "delivered" << YAML::Value << l.delivered;
    out << YAML::Key << "lost" << YAML::Value << l.lost;
    out << YAML::Key << "outage" << YAML::Value << l.outage;
    out << YAML::Key << "queue" << YAML::Value << l.queue;
    out << YAML::Key << "duplicated" << YAML::Value << l.duplicated;
    out << YAML::Key << "reordered" << YAML::Value << l.reordered;
    out << YAML::Key << "loss_burst_mean" << YAML::Value << l.loss_burst_mean;
    out << YAML::Key << "loss_burst_max" << YAML::Value << l.loss_burst_max;
    out << YAML::Key << "delay_p50_ns" << YAML::Value << l.delay_p50_ns;
    out << YAML::Key << "delay_p99_ns" << YAML::Value << l.delay_p99_ns;
    out << YAML::Key << "delay_max_ns" << YAML::Value << l.delay_max_ns;
    out << YAML::Key << "configured_loss" << YAML::Value << l.configured_loss;
    out << YAML::Key << "configured_delay_ns" << YAML::Value << l.configured_delay_ns;
    out << YAML::EndMap;
  }
  out << YAML::EndSeq;
  out << YAML::Key << "counters" << YAML::Value << YAML::BeginMap;
  for (const auto& [name, value] : report.counters) out << YAML::Key << name << YAML::Value << value;
  out << YAML::EndMap;
  out << YAML::EndMap;

  std::ofstream file(path);
  file << out.c_str() << "\n";
  if (!file) throw std::runtime_error("cannot write report " + path);
}

NodeReport read_report(const std::string& path) {
  const ConfigNode root = ConfigNode::load_file(path);
  constexpr Range kAny{-1e18, 1e18};
  constexpr Range kCount{0, 1e19};
  NodeReport r;
  r.name = root.get_string("name");
  r.role = root.get_string("role");
  r.final_state = root.get_string("final_state");
  r.rate_hz = root.get_double("rate_hz", kAny);
  r.run_time_s = root.get_double("run_time_s", kAny);
  r.cycles = static_cast<uint64_t>(root.get_double("cycles", kCount));
  r.overruns = static_cast<uint64_t>(root.get_double("overruns", kCount));
  r.skipped = static_cast<uint64_t>(root.get_double("skipped", kCount));
  r.lateness_p50_ns = root.get_int("lateness_p50_ns", kAny);
  r.lateness_p99_ns = root.get_int("lateness_p99_ns", kAny);
  r.lateness_max_ns = root.get_int("lateness_max_ns", kAny);
  r.shutdown_ms = root.get_double("shutdown_ms", kAny);
  for (const auto& p : root.get_node_list("published")) {
    r.published.push_back({p.get_string("topic"), static_cast<uint64_t>(p.get_double("sent", kCount)),
                           static_cast<uint64_t>(p.get_double("failed", kCount))});
  }
  for (const auto& n : root.get_node_list("received")) {
    ReceivedTopic t;
    t.topic = n.get_string("topic");
    t.received = static_cast<uint64_t>(n.get_double("received", kCount));
    t.expected = static_cast<uint64_t>(n.get_double("expected", kCount));
    t.lost = static_cast<uint64_t>(n.get_double("lost", kCount));
    t.duplicates = static_cast<uint64_t>(n.get_double("duplicates", kCount));
    t.reordered = static_cast<uint64_t>(n.get_double("reordered", kCount));
    t.first_seq = static_cast<uint64_t>(n.get_double("first_seq", kCount));
    t.last_seq = static_cast<uint64_t>(n.get_double("last_seq", kCount));
    t.rate_hz = n.get_double("rate_hz", kAny);
    t.latency_p50_ns = n.get_int("latency_p50_ns", kAny);
    t.latency_p99_ns = n.get_int("latency_p99_ns", kAny);
    t.latency_max_ns = n.get_int("latency_max_ns", kAny);
    t.deadline_missed = static_cast<uint64_t>(n.get_double("deadline_missed", kCount));
    t.liveliness_lost = static_cast<uint64_t>(n.get_double("liveliness_lost", kCount));
    t.gap_max = static_cast<uint64_t>(n.get_double("gap_max", kCount, 0));
    t.gap_mean = n.get_double("gap_mean", kAny, 0);
    t.age_p50_ns = n.get_int("age_p50_ns", kAny, 0);
    t.age_p99_ns = n.get_int("age_p99_ns", kAny, 0);
    t.age_max_ns = n.get_int("age_max_ns", kAny, 0);
    r.received.push_back(t);
  }
  r.impairment_seed = static_cast<uint64_t>(root.get_double("impairment_seed", kCount, 0));
  for (const auto& n : root.get_node_list("links")) {
    ImpairedLink l;
    l.to = n.get_string("to");
    l.profile = n.get_string("profile");
    l.messages = static_cast<uint64_t>(n.get_double("messages", kCount));
    l.delivered = static_cast<uint64_t>(n.get_double("delivered", kCount));
    l.lost = static_cast<uint64_t>(n.get_double("lost", kCount));
    l.outage = static_cast<uint64_t>(n.get_double("outage", kCount));
    l.queue = static_cast<uint64_t>(n.get_double("queue", kCount));
    l.duplicated = static_cast<uint64_t>(n.get_double("duplicated", kCount));
    l.reordered = static_cast<uint64_t>(n.get_double("reordered", kCount));
    l.loss_burst_mean = n.get_double("loss_burst_mean", kAny);
    l.loss_burst_max = static_cast<uint64_t>(n.get_double("loss_burst_max", kCount));
    l.delay_p50_ns = n.get_int("delay_p50_ns", kAny);
    l.delay_p99_ns = n.get_int("delay_p99_ns", kAny);
    l.delay_max_ns = n.get_int("delay_max_ns", kAny);
    l.configured_loss = n.get_double("configured_loss", kAny);
    l.configured_delay_ns = n.get_int("configured_delay_ns", kAny);
    r.links.push_back(l);
  }
  if (auto counters = root.optional_child("counters")) {
    for (const auto& key : counters->keys()) r.counters.emplace_back(key, counters->get_double(key, kAny));
  }
  return r;
}

}  // namespace teleop::runtime
