#include "teleop/runtime/node_report.h"

#include <yaml-cpp/yaml.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <type_traits>
#include <variant>

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
                                        uint64_t liveliness_lost, const StreamSession& session) {
  ReceivedTopic r;
  r.sessions = stats.sessions();
  r.refused_other_writer = session.refused_other_writer();
  r.refused_sequence_jump = session.refused_sequence_jump();
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

namespace {

constexpr Range kAny{-1e18, 1e18};
constexpr Range kCount{0, 1e19};

// one entry per field of a report struct: its YAML key and member; the writer and the reader both
// walk these tables, so a field is named once. Fields added after reports were first written are
// optional on reading (older reports lack them).
template <typename S>
struct Field {
  const char* key;
  std::variant<std::string S::*, double S::*, uint64_t S::*, int64_t S::*> member;
  bool optional = false;
};

template <typename S>
void write_fields(YAML::Emitter& out, const S& s, std::initializer_list<Field<S>> fields) {
  for (const Field<S>& f : fields) {
    out << YAML::Key << f.key << YAML::Value;
    std::visit([&](auto member) { out << s.*member; }, f.member);
  }
}

template <typename S>
void read_fields(const ConfigNode& n, S& s, std::initializer_list<Field<S>> fields) {
  for (const Field<S>& f : fields) {
    std::visit(
        [&](auto member) {
          using T = std::remove_reference_t<decltype(s.*member)>;
          if (f.optional && !n.has(f.key)) {
            n.get_string(f.key, "");  // marks it as read; the default stays
            return;
          }
          if constexpr (std::is_same_v<T, std::string>) {
            s.*member = n.get_string(f.key);
          } else if constexpr (std::is_same_v<T, double>) {
            s.*member = n.get_double(f.key, kAny);
          } else if constexpr (std::is_same_v<T, uint64_t>) {
            // counts may exceed int64: read as a number
            s.*member = static_cast<uint64_t>(n.get_double(f.key, kCount));
          } else {
            s.*member = n.get_int(f.key, kAny);
          }
        },
        f.member);
  }
}

const std::initializer_list<Field<NodeReport>> kReportFields{
    {"name", &NodeReport::name},
    {"role", &NodeReport::role},
    {"final_state", &NodeReport::final_state},
    {"rate_hz", &NodeReport::rate_hz},
    {"run_time_s", &NodeReport::run_time_s},
    {"cycles", &NodeReport::cycles},
    {"overruns", &NodeReport::overruns},
    {"skipped", &NodeReport::skipped},
    {"lateness_p50_ns", &NodeReport::lateness_p50_ns},
    {"lateness_p99_ns", &NodeReport::lateness_p99_ns},
    {"lateness_max_ns", &NodeReport::lateness_max_ns},
    {"shutdown_ms", &NodeReport::shutdown_ms},
};

const std::initializer_list<Field<PublishedTopic>> kPublishedFields{
    {"topic", &PublishedTopic::topic},
    {"sent", &PublishedTopic::sent},
    {"failed", &PublishedTopic::failed},
    {"write_p99_ns", &PublishedTopic::write_p99_ns, true},
    {"write_max_ns", &PublishedTopic::write_max_ns, true},
};

const std::initializer_list<Field<ReceivedTopic>> kReceivedFields{
    {"topic", &ReceivedTopic::topic},
    {"received", &ReceivedTopic::received},
    {"expected", &ReceivedTopic::expected},
    {"lost", &ReceivedTopic::lost},
    {"duplicates", &ReceivedTopic::duplicates},
    {"reordered", &ReceivedTopic::reordered},
    {"first_seq", &ReceivedTopic::first_seq},
    {"last_seq", &ReceivedTopic::last_seq},
    {"rate_hz", &ReceivedTopic::rate_hz},
    {"latency_p50_ns", &ReceivedTopic::latency_p50_ns},
    {"latency_p99_ns", &ReceivedTopic::latency_p99_ns},
    {"latency_max_ns", &ReceivedTopic::latency_max_ns},
    {"deadline_missed", &ReceivedTopic::deadline_missed},
    {"liveliness_lost", &ReceivedTopic::liveliness_lost},
    {"gap_max", &ReceivedTopic::gap_max, true},
    {"gap_mean", &ReceivedTopic::gap_mean, true},
    {"age_p50_ns", &ReceivedTopic::age_p50_ns, true},
    {"age_p99_ns", &ReceivedTopic::age_p99_ns, true},
    {"age_max_ns", &ReceivedTopic::age_max_ns, true},
    {"sessions", &ReceivedTopic::sessions, true},
    {"refused_other_writer", &ReceivedTopic::refused_other_writer, true},
    {"refused_sequence_jump", &ReceivedTopic::refused_sequence_jump, true},
    {"refused_not_accepted", &ReceivedTopic::refused_not_accepted, true},
    {"refused_invalid", &ReceivedTopic::refused_invalid, true},
    {"clock_offset_ns", &ReceivedTopic::clock_offset_ns, true},
    {"clock_offset_max_ns", &ReceivedTopic::clock_offset_max_ns, true},
};

const std::initializer_list<Field<ImpairedLink>> kLinkFields{
    {"to", &ImpairedLink::to},
    {"profile", &ImpairedLink::profile},
    {"messages", &ImpairedLink::messages},
    {"delivered", &ImpairedLink::delivered},
    {"lost", &ImpairedLink::lost},
    {"outage", &ImpairedLink::outage},
    {"queue", &ImpairedLink::queue},
    {"duplicated", &ImpairedLink::duplicated},
    {"reordered", &ImpairedLink::reordered},
    {"loss_burst_mean", &ImpairedLink::loss_burst_mean},
    {"loss_burst_max", &ImpairedLink::loss_burst_max},
    {"delay_p50_ns", &ImpairedLink::delay_p50_ns},
    {"delay_p99_ns", &ImpairedLink::delay_p99_ns},
    {"delay_max_ns", &ImpairedLink::delay_max_ns},
    {"configured_loss", &ImpairedLink::configured_loss},
    {"configured_delay_ns", &ImpairedLink::configured_delay_ns},
};

template <typename S>
void write_list(YAML::Emitter& out, const char* key, const std::vector<S>& items, std::initializer_list<Field<S>> fields,
                bool flow = false) {
  out << YAML::Key << key << YAML::Value << YAML::BeginSeq;
  for (const S& item : items) {
    if (flow) out << YAML::Flow;
    out << YAML::BeginMap;
    write_fields(out, item, fields);
    out << YAML::EndMap;
  }
  out << YAML::EndSeq;
}

template <typename S>
std::vector<S> read_list(const ConfigNode& root, const char* key, std::initializer_list<Field<S>> fields) {
  std::vector<S> items;
  for (const auto& n : root.get_node_list(key)) read_fields(n, items.emplace_back(), fields);
  return items;
}

}  // namespace

void write_report(const NodeReport& report, const std::string& path) {
  YAML::Emitter out;
  out << YAML::BeginMap;
  write_fields(out, report, kReportFields);
  write_list(out, "published", report.published, kPublishedFields, true);
  write_list(out, "received", report.received, kReceivedFields);
  out << YAML::Key << "impairment_seed" << YAML::Value << report.impairment_seed;
  write_list(out, "links", report.links, kLinkFields);
  out << YAML::Key << "counters" << YAML::Value << YAML::BeginMap;
  for (const auto& [name, value] : report.counters) out << YAML::Key << name << YAML::Value << value;
  out << YAML::EndMap;
  out << YAML::EndMap;

  errno = 0;
  std::ofstream file(path);
  file << out.c_str() << "\n";
  // closed before the check: a full disk refuses the buffered text only when it is flushed
  file.close();
  if (!file) {
    throw std::runtime_error("cannot write report " + path +
                             (errno != 0 ? std::string(": ") + std::strerror(errno) : ""));
  }
}

NodeReport read_report(const std::string& path) {
  const ConfigNode root = ConfigNode::load_file(path);
  NodeReport r;
  read_fields(root, r, kReportFields);
  r.published = read_list(root, "published", kPublishedFields);
  r.received = read_list(root, "received", kReceivedFields);
  r.impairment_seed = static_cast<uint64_t>(root.get_double("impairment_seed", kCount, 0));
  r.links = read_list(root, "links", kLinkFields);
  if (auto counters = root.optional_child("counters")) {
    for (const auto& key : counters->keys()) r.counters.emplace_back(key, counters->get_double(key, kAny));
  }
  return r;
}

}  // namespace teleop::runtime
