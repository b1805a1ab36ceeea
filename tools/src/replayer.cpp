#include "teleop/tools/replayer.h"

#include <spdlog/fmt/fmt.h>

#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "bus.h"
#include "joint_state_track.h"
#include "teleop/bag/bag_reader.h"
#include "teleop/common/clock.h"
#include "teleop/runtime/shutdown_signal.h"
#include "teleop/tools/sample_text.h"

namespace teleop::tools {
namespace {

std::vector<int> topics_to_replay(const bag::BagReader& reader, const ReplayOptions& options) {
  std::vector<int> ids;
  if (options.topics.empty()) {
    for (const bag::TopicInfo& t : reader.topics()) {
      if (t.name != options.compare_topic) ids.push_back(reader.topic_id(t.name));
    }
    return ids;
  }
  for (const std::string& name : options.topics) {
    const int id = reader.topic_id(name);
    if (id < 0) {
      std::string known;
      for (const bag::TopicInfo& t : reader.topics()) known += "\n  " + t.name;
      throw std::runtime_error(fmt::format("{}: the recording has no topic {}; it has:{}", options.dir, name, known));
    }
    ids.push_back(id);
  }
  return ids;
}

const bag::TopicInfo& topic_in_bag(const bag::BagReader& reader, int topic_id) {
  for (const bag::TopicInfo& t : reader.topics()) {
    if (reader.topic_id(t.name) == topic_id) return t;
  }
  throw std::runtime_error(fmt::format("topic id {} is not in the recording", topic_id));
}

const transport::SampleType& type_of(const bag::TopicInfo& topic) {
  if (const transport::SampleType* type = transport::find_sample_type(topic.type)) return *type;
  throw std::runtime_error(fmt::format("{}: type {} is not a teleop type (idl/)", topic.name, topic.type));
}

void sleep_until_mono(int64_t deadline_ns) {
  timespec ts{static_cast<time_t>(deadline_ns / 1'000'000'000), static_cast<long>(deadline_ns % 1'000'000'000)};
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR && !runtime::shutdown_requested()) {
  }
}

void wait_for_readers(std::map<int, transport::RawWriter>& writers, double seconds, const std::string& name_hint,
                      FILE* log) {
  const int64_t deadline_ns = monotonic_now_ns() + static_cast<int64_t>(seconds * 1e9);
  const auto all_matched = [&] {
    return std::all_of(writers.begin(), writers.end(), [](const auto& w) { return w.second.matched() > 0; });
  };
  while (!all_matched() && monotonic_now_ns() < deadline_ns && !runtime::shutdown_requested()) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  if (!all_matched()) std::fprintf(log, "replaying %s although not every topic has a reader yet\n", name_hint.c_str());
}

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  const size_t k = std::min(v.size() - 1, static_cast<size_t>(p * static_cast<double>(v.size())));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

// one pass over the recording at `rate`, from `start_ns`; returns the first message's recorded time
int64_t play_once(bag::BagReader& reader, std::map<int, transport::RawWriter>& writers, const ReplayOptions& options,
                  int64_t start_ns, std::vector<double>& errors_s, uint64_t& published) {
  std::vector<int> ids;
  for (const auto& [id, w] : writers) ids.push_back(id);
  reader.select(ids);
  bag::BagMessage m;
  int64_t first_ns = -1;
  while (!runtime::shutdown_requested() && reader.next(m)) {
    const int64_t recorded_ns = bag::pacing_time_ns(m);
    if (first_ns < 0) first_ns = recorded_ns;
    const int64_t due_ns =
        start_ns + static_cast<int64_t>(static_cast<double>(recorded_ns - first_ns) / options.rate);
    sleep_until_mono(due_ns);
    const int64_t now_ns = monotonic_now_ns();
    if (!options.keep_stamps) restamp_header(m.data, system_now_ns(), now_ns);
    if (writers.at(m.topic_id).write(m.data)) ++published;
    errors_s.push_back(static_cast<double>(now_ns - due_ns) * 1e-9);
  }
  return first_ns;
}

}  // namespace

ReplayResult replay(const BusOptions& bus_options, const ReplayOptions& options, FILE* log) {
  bag::BagReader reader(options.dir);
  if (!reader.warning().empty()) std::fprintf(log, "%s\n", reader.warning().c_str());
  const std::vector<int> ids = topics_to_replay(reader, options);
  // the recorded half of the comparison, before anything is published
  JointStateTrack recorded;
  if (!options.compare_topic.empty()) recorded = JointStateTrack::from_bag(reader, options.compare_topic);
  JointStateTrack live;  // outlives the bus: its reader adds to it until the bus is gone
  std::mutex live_mutex;
  Bus bus(bus_options, "teleop_replay");
  std::map<int, transport::RawWriter> writers;
  std::string names;
  for (int id : ids) {
    const bag::TopicInfo& topic = topic_in_bag(reader, id);
    const std::string& name = topic.name;
    writers[id] = bus.participant().make_raw_writer(name, type_of(topic), transport::topic_qos(name));
    names += (names.empty() ? "" : ", ") + name;
  }
  if (!options.compare_topic.empty()) {
    const transport::SampleType* type = transport::find_sample_type("teleop::msg::JointState");
    bus.participant().make_raw_reader(options.compare_topic, *type, transport::topic_qos(options.compare_topic),
                                      [&](const transport::RawSample& s) {
                                        std::lock_guard lock(live_mutex);
                                        live.add(monotonic_now_ns(), s.cdr);
                                      });
  }
  wait_for_readers(writers, options.wait_for_readers_s, names, log);
  std::fprintf(log, "replaying %s at %gx\n", names.c_str(), options.rate);
  std::fflush(log);

  ReplayResult result;
  std::vector<double> errors_s;
  const int64_t start_ns = monotonic_now_ns() + 10'000'000;
  const int64_t first_ns = play_once(reader, writers, options, start_ns, errors_s, result.published);
  while (options.loop && !runtime::shutdown_requested()) {
    play_once(reader, writers, options, monotonic_now_ns() + 10'000'000, errors_s, result.published);
  }
  if (!options.compare_topic.empty() && first_ns >= 0) {
    std::this_thread::sleep_for(std::chrono::milliseconds(200));  // the last live samples
    std::lock_guard lock(live_mutex);
    const TrackComparison c = compare_tracks(live, start_ns, recorded, first_ns, options.rate);
    result.compared = c.samples;
    result.rmse = c.rmse;
    result.max_error = c.max_error;
  }
  result.timing_error_p50_s = percentile(errors_s, 0.5);
  result.timing_error_p99_s = percentile(errors_s, 0.99);
  result.timing_error_max_s = errors_s.empty() ? 0.0 : *std::max_element(errors_s.begin(), errors_s.end());
  std::vector<double> interval_errors_s;
  for (size_t i = 1; i < errors_s.size(); ++i) interval_errors_s.push_back(std::abs(errors_s[i] - errors_s[i - 1]));
  result.interval_error_p50_s = percentile(interval_errors_s, 0.5);
  result.interval_error_p99_s = percentile(interval_errors_s, 0.99);
  return result;
}

std::string format_replay(const ReplayResult& r, const ReplayOptions& options) {
  std::string text = fmt::format(
      "replayed {} samples; timing error p50 {:.3f} ms p99 {:.3f} ms max {:.3f} ms; interval error p50 {:.3f} ms "
      "p99 {:.3f} ms\n",
      r.published, r.timing_error_p50_s * 1e3, r.timing_error_p99_s * 1e3, r.timing_error_max_s * 1e3,
      r.interval_error_p50_s * 1e3, r.interval_error_p99_s * 1e3);
  if (!options.compare_topic.empty()) {
    text += fmt::format("compare {}: {} live samples, RMSE {:.6f} rad, max error {:.6f} rad\n", options.compare_topic,
                        r.compared, r.rmse, r.max_error);
  }
  return text;
}

}  // namespace teleop::tools
