#include "teleop/tools/topic_tools.h"

#include <spdlog/fmt/fmt.h>

#include <chrono>
#include <condition_variable>
#include <deque>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "bus.h"
#include "teleop/common/clock.h"
#include "teleop/runtime/shutdown_signal.h"
#include "teleop/tools/rate_meter.h"
#include "teleop/tools/sample_text.h"

namespace teleop::tools {
namespace {

// samples handed over from Fast DDS's thread to the tool's, at most `capacity` waiting
class SampleQueue {
 public:
  explicit SampleQueue(size_t capacity) : capacity_(capacity) {}
  void push(const transport::RawSample& s) {
    std::lock_guard lock(mutex_);
    if (queue_.size() >= capacity_) return;  // echo keeps up with a person, not with 1 kHz
    queue_.push_back(s);
    ready_.notify_one();
  }
  bool pop(transport::RawSample& out, std::chrono::milliseconds timeout) {
    std::unique_lock lock(mutex_);
    if (!ready_.wait_for(lock, timeout, [&] { return !queue_.empty(); })) return false;
    out = std::move(queue_.front());
    queue_.pop_front();
    return true;
  }

 private:
  size_t capacity_;
  std::mutex mutex_;
  std::condition_variable ready_;
  std::deque<transport::RawSample> queue_;
};

void print_hz_line(const std::string& topic, const RateStats& s, FILE* out) {
  std::fprintf(out,
               "%s: rate %.1f Hz  period mean %.3f ms min %.3f ms max %.3f ms std %.3f ms  window %llu  "
               "age mean %.3f ms max %.3f ms  lost %llu\n",
               topic.c_str(), s.rate_hz, s.period_mean_s * 1e3, s.period_min_s * 1e3, s.period_max_s * 1e3,
               s.period_std_s * 1e3, static_cast<unsigned long long>(s.window), s.age_mean_s * 1e3, s.age_max_s * 1e3,
               static_cast<unsigned long long>(s.lost));
  std::fflush(out);
}

void print_hz_total(const RateStats& s, FILE* out) {
  std::fprintf(out, "total: received %llu lost %llu first_seq %llu last_seq %llu span %.6f s\n",
               static_cast<unsigned long long>(s.received), static_cast<unsigned long long>(s.lost),
               static_cast<unsigned long long>(s.first_seq), static_cast<unsigned long long>(s.last_seq), s.span_s);
}

}  // namespace

int topic_list(const BusOptions& options, bool verbose, FILE* out) {
  Bus bus(options, "teleop_topic");
  bus.listen();
  const auto topics = bus.topics();
  std::fputs(format_topic_list(topics, verbose).c_str(), out);
  if (topics.empty()) std::fprintf(stderr, "no topics in domain %d after %g s\n", bus.domain_id(), options.discovery_s);
  return 0;
}

int topic_info(const BusOptions& options, const std::string& topic, FILE* out) {
  Bus bus(options, "teleop_topic");
  bus.listen();
  for (const TopicView& t : bus.topics()) {
    if (t.name != topic) continue;
    std::fputs(format_topic_info(t).c_str(), out);
    return 0;
  }
  std::fprintf(stderr, "teleop topic info: no writer or reader of %s in domain %d within %g s\n", topic.c_str(),
               bus.domain_id(), options.discovery_s);
  return 1;
}

int topic_echo(const BusOptions& options, const EchoOptions& echo, FILE* out) {
  SampleQueue queue(64);  // before the bus: its reader hands samples in until the bus is gone
  Bus bus(options, "teleop_topic");
  const auto topic = bus.wait_for_writers(echo.topic);
  if (!topic) throw std::runtime_error(no_writer_message(echo.topic, bus));
  const transport::SampleType& type = Bus::type_of(*topic);
  bus.participant().make_raw_reader(echo.topic, type, transport::topic_qos(echo.topic),
                                    [&](const transport::RawSample& s) { queue.push(s); });
  transport::RawSample sample;
  for (uint64_t printed = 0; (echo.count == 0 || printed < echo.count) && !runtime::shutdown_requested();) {
    if (!queue.pop(sample, std::chrono::milliseconds(100))) continue;
    // a bad field throws on the first sample, before anything misleading is printed
    std::fputs(sample_text(type, sample.cdr, echo.field).c_str(), out);
    if (echo.field.empty()) std::fputs("---\n", out);
    std::fflush(out);
    ++printed;
  }
  return 0;
}

int topic_hz(const BusOptions& options, const HzOptions& hz, FILE* out) {
  // before the bus: its reader adds to them until the bus is gone
  std::mutex mutex;
  RateMeter meter(hz.window);
  Bus bus(options, "teleop_topic");
  const auto topic = bus.wait_for_writers(hz.topic);
  if (!topic) throw std::runtime_error(no_writer_message(hz.topic, bus));
  bus.participant().make_raw_reader(
      hz.topic, Bus::type_of(*topic), transport::topic_qos(hz.topic), [&](const transport::RawSample& s) {
        HeaderView header;
        if (!read_header(s.cdr, header)) return;
        std::lock_guard lock(mutex);
        meter.add(monotonic_now_ns(), s.reception_ns - header.stamp_ns, s.writer, header.seq);
      });
  const auto snapshot = [&] {
    std::lock_guard lock(mutex);
    return meter.stats();
  };
  // the loop looks at the count only: the statistics (and the lock the receiving thread waits
  // for while they are computed) once a line is due
  const auto received = [&] {
    std::lock_guard lock(mutex);
    return meter.received();
  };
  const int64_t start_ns = monotonic_now_ns();
  int64_t next_line_ns = start_ns + 1'000'000'000;
  while (!runtime::shutdown_requested()) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    const int64_t now_ns = monotonic_now_ns();
    if (hz.count > 0 && received() >= hz.count) break;
    if (hz.duration_s > 0 && now_ns - start_ns >= static_cast<int64_t>(hz.duration_s * 1e9)) break;
    if (now_ns >= next_line_ns) {
      next_line_ns += 1'000'000'000;
      const RateStats s = snapshot();
      if (s.received == 0) {
        std::fprintf(out, "%s: no sample yet\n", hz.topic.c_str());
      } else {
        print_hz_line(hz.topic, s, out);
      }
    }
  }
  const RateStats s = snapshot();
  if (s.received > 0) print_hz_line(hz.topic, s, out);
  print_hz_total(s, out);
  return s.received > 0 ? 0 : 1;
}

}  // namespace teleop::tools
