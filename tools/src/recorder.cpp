#include "teleop/tools/recorder.h"

#include <spdlog/fmt/fmt.h>

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <map>
#include <mutex>
#include <set>
#include <thread>

#include "bus.h"
#include "teleop/bag/bag_writer.h"
#include "teleop/common/clock.h"
#include "teleop/runtime/shutdown_signal.h"
#include "teleop/tools/sample_text.h"

namespace teleop::tools {
namespace {

struct Received {
  int topic_id;
  int64_t recv_ns;
  int64_t recv_mono_ns;
  transport::RawSample sample;
};

// from Fast DDS's threads to the disk thread, bounded
class DiskQueue {
 public:
  explicit DiskQueue(size_t capacity) : capacity_(capacity) {}
  void push(Received&& r) {
    std::lock_guard lock(mutex_);
    if (queue_.size() >= capacity_) {
      ++dropped_;
      return;
    }
    queue_.push_back(std::move(r));
    ready_.notify_one();
  }
  /// Swaps the waiting samples into `out` (empty when none came within the timeout).
  void take(std::vector<Received>& out, std::chrono::milliseconds timeout) {
    out.clear();
    std::unique_lock lock(mutex_);
    ready_.wait_for(lock, timeout, [&] { return !queue_.empty(); });
    out.swap(queue_);
  }
  uint64_t dropped() const {
    std::lock_guard lock(mutex_);
    return dropped_;
  }

 private:
  size_t capacity_;
  mutable std::mutex mutex_;
  std::condition_variable ready_;
  std::vector<Received> queue_;
  uint64_t dropped_ = 0;
};

// sequence gaps per writer of each topic: what the network or the node lost before the recorder
class GapCounter {
 public:
  void add(int topic_id, const transport::RawSample& s) {
    HeaderView h;
    if (!read_header(s.cdr, h)) return;
    auto [it, first] = last_.try_emplace({topic_id, s.writer.bytes}, h.seq);
    if (!first && h.seq > it->second) {
      missed_ += h.seq - it->second - 1;
      it->second = h.seq;
    }
  }
  uint64_t missed() const { return missed_; }

 private:
  std::map<std::pair<int, std::array<uint8_t, 16>>, uint64_t> last_;
  uint64_t missed_ = 0;
};

std::string qos_yaml(transport::QosPreset preset) {
  // rosbag2's offered_qos_profiles, for the one profile every writer of a teleop topic uses
  const bool reliable = preset != transport::QosPreset::kStream;
  const bool transient = preset == transport::QosPreset::kState;
  return fmt::format("- history: 1\n  depth: 1\n  reliability: {}\n  durability: {}\n", reliable ? 1 : 2,
                     transient ? 1 : 2);
}

bool wanted(const RecordOptions& options, const std::string& topic) {
  return options.topics.empty() || std::find(options.topics.begin(), options.topics.end(), topic) != options.topics.end();
}

double cpu_seconds() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  const auto s = [](const timeval& t) { return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_usec) * 1e-6; };
  return s(usage.ru_utime) + s(usage.ru_stime);
}

}  // namespace

RecordResult record(const BusOptions& bus_options, const RecordOptions& options, FILE* log) {
  DiskQueue queue(options.queue_capacity);  // outlives the bus: its readers push until it is gone
  bag::BagWriter bag(bag::BagWriterOptions{options.dir});
  auto bus = std::make_unique<Bus>(bus_options, "teleop_record");
  std::set<std::string> subscribed;
  RecordResult result;

  std::mutex bag_mutex;  // the disk thread writes, this one adds topics
  std::atomic<bool> stop_disk{false};
  GapCounter gaps;
  std::vector<Received> batch;
  const auto write_batch = [&](std::chrono::milliseconds wait) {
    queue.take(batch, wait);
    std::lock_guard lock(bag_mutex);
    for (const Received& r : batch) {
      bag.write(r.topic_id, r.recv_ns, r.recv_mono_ns, r.sample.writer.bytes, r.sample.cdr.data(), r.sample.cdr.size());
      gaps.add(r.topic_id, r.sample);
    }
    if (batch.empty()) bag.poll();  // quiet: commit on time all the same, so a kill loses at most a period
  };
  std::thread disk([&] {
    while (!stop_disk.load()) write_batch(std::chrono::milliseconds(100));
  });

  const int64_t start_ns = monotonic_now_ns();
  const auto subscribe = [&](const std::string& name, const transport::SampleType& type) {
    const transport::QosPreset qos = transport::topic_qos(name);
    const int id = [&] {
      std::lock_guard lock(bag_mutex);
      return bag.add_topic({name, type.bag_name, qos_yaml(qos)});
    }();
    bus->participant().make_raw_reader(name, type, qos, [&queue, id](const transport::RawSample& s) {
      queue.push({id, s.reception_ns, monotonic_now_ns(), s});
    });
    subscribed.insert(name);
    result.topics.push_back(name);
    std::fprintf(log, "recording %s (%s)\n", name.c_str(), type.bag_name.c_str());
    std::fflush(log);
  };
  // the fixed topics at once, so that a node starting after the recorder loses no first sample
  for (const transport::KnownTopic& k : transport::known_topics()) {
    if (wanted(options, k.name)) subscribe(k.name, *k.type);
  }
  // the families (one topic per object, per contact pair) as discovery finds them
  const auto subscribe_new_topics = [&] {
    for (const TopicView& t : bus->topics()) {
      if (t.writers.empty() || subscribed.count(t.name) > 0 || !wanted(options, t.name)) continue;
      const transport::SampleType* type = t.types.size() == 1 ? transport::find_sample_type(t.types.front()) : nullptr;
      if (type != nullptr) subscribe(t.name, *type);  // not ours: nothing to decode it with later
    }
  };
  while (!runtime::shutdown_requested()) {
    subscribe_new_topics();
    if (options.duration_s > 0 && monotonic_now_ns() - start_ns >= static_cast<int64_t>(options.duration_s * 1e9)) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  bus.reset();  // no sample arrives after this
  stop_disk.store(true);
  disk.join();
  write_batch(std::chrono::milliseconds(0));  // what was still queued
  bag.close();
  result.messages = bag.stats().messages;
  result.bytes = bag.stats().bytes;
  result.dropped = queue.dropped();
  result.missed = gaps.missed();
  result.seconds = static_cast<double>(monotonic_now_ns() - start_ns) * 1e-9;
  result.cpu_s = cpu_seconds();
  for (const std::string& t : options.topics) {
    if (subscribed.count(t) == 0) std::fprintf(log, "no writer of %s appeared: not recorded\n", t.c_str());
  }
  return result;
}

}  // namespace teleop::tools
