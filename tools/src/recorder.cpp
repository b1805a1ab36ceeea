#include "teleop/tools/recorder.h"

#include <spdlog/fmt/fmt.h>

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <map>
#include <mutex>
#include <thread>

#include "teleop/bag/bag_writer.h"
#include "teleop/bag/mcap_writer.h"
#include "teleop/common/clock.h"
#include "teleop/common/config.h"
#include "teleop/common/did_you_mean.h"
#include "teleop/runtime/shutdown_signal.h"
#include "teleop/tools/bus_tap.h"
#include "teleop/tools/sample_text.h"
#include "teleop/transport/topics.h"

namespace teleop::tools {
namespace {

struct Received {
  int topic_id;
  int64_t recv_ns;
  int64_t recv_mono_ns;
  transport::RawSample sample;
};

std::unique_ptr<bag::RecordingWriter> open_writer(const RecordOptions& options) {
  if (options.format == RecordingFormat::kSqlite3) {
    return std::make_unique<bag::BagWriter>(
        bag::BagWriterOptions{options.dir, 200'000'000, 1'000'000'000, options.max_bytes});
  }
  bag::McapWriterOptions mcap{options.dir};
  mcap.compression = options.compression;
  mcap.max_bytes = options.max_bytes;
  return std::make_unique<bag::McapWriter>(mcap);
}

// the writer's stamp: MCAP's publish_time (0 when the payload has no header to read it from)
int64_t publish_time_ns(const transport::RawSample& s) {
  HeaderView h;
  return read_header(s.cdr, h) ? h.stamp_ns : 0;
}

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

// a member of a topic family: the family's prefix and a name after it
bool in_family(const std::string& topic) {
  for (const std::string_view prefix : {transport::topics::kFollowerObjectPosePrefix, transport::topics::kTwinContactWrenchPrefix}) {
    if (topic.size() > prefix.size() && topic.compare(0, prefix.size(), prefix) == 0) return true;
  }
  return false;
}

double cpu_seconds() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  const auto s = [](const timeval& t) { return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_usec) * 1e-6; };
  return s(usage.ru_utime) + s(usage.ru_stime);
}

// One recording: the bus's readers feed the queue, a disk thread empties it into the bag. A disk
// error (a full disk, the size cap) ends the recording; what was committed stays readable.
class Recording {
 public:
  Recording(const BusOptions& bus_options, const RecordOptions& options, FILE* log)
      : options_(options),
        log_(log),
        queue_(options.queue_capacity),
        bag_(open_writer(options)),
        tap_(std::make_unique<BusTap>(
            bus_options, "teleop_record", options.topics, [this](const TappedTopic& t) { return add_topic(t); },
            [this](int id, const transport::RawSample& s) { queue_.push({id, s.reception_ns, monotonic_now_ns(), s}); })),
        disk_([this] { disk_loop(); }) {}

  ~Recording() {
    if (disk_.joinable()) stop_disk();
  }

  // the fixed topics at once, so that a node starting after the recorder loses no first sample;
  // the families (one topic per object, per contact pair) as discovery finds them
  void subscribe_known_topics() { tap_->subscribe_known_topics(); }
  void subscribe_new_topics() { tap_->subscribe_new_topics(); }

  bool failed() const { return failed_.load(); }

  /// Stops the bus, writes what is queued, closes the bag. Throws the disk's error, if any.
  RecordResult finish() {
    tap_->close();  // no sample arrives after this
    stop_disk();
    if (!failed()) guarded([&] { write_batch(std::chrono::milliseconds(0)); });  // what was still queued
    guarded([&] { bag_->close(); });
    if (failed()) throw bag::BagError(error_ + "; what was recorded before stays readable in " + options_.dir);
    RecordResult result;
    result.messages = bag_->stats().messages;
    result.bytes = bag_->stats().bytes;
    result.dropped = queue_.dropped();
    result.missed = gaps_.missed();
    result.topics.assign(tap_->subscribed().begin(), tap_->subscribed().end());
    for (const std::string& t : options_.topics) {
      if (tap_->subscribed().count(t) == 0) std::fprintf(log_, "no writer of %s appeared: not recorded\n", t.c_str());
    }
    return result;
  }

 private:
  // the tap's new topic: a topic of the bag
  int add_topic(const TappedTopic& topic) {
    const int id = [&] {
      std::lock_guard lock(bag_mutex_);
      return bag_->add_topic(recorded_topic(topic.name, *topic.type, qos_yaml(topic.qos), options_.format));
    }();
    std::fprintf(log_, "recording %s (%s)\n", topic.name.c_str(), topic.type->bag_name.c_str());
    std::fflush(log_);
    return id;
  }

  void write_batch(std::chrono::milliseconds wait) {
    queue_.take(batch_, wait);
    std::lock_guard lock(bag_mutex_);
    for (const Received& r : batch_) {
      bag_->write({r.topic_id, r.recv_ns, r.recv_mono_ns, publish_time_ns(r.sample), r.sample.writer.bytes,
                   r.sample.cdr.data(), r.sample.cdr.size()});
      gaps_.add(r.topic_id, r.sample);
    }
    if (batch_.empty()) bag_->poll();  // quiet: commit (write the chunk) on time all the same: a kill loses at most a period
  }

  void disk_loop() {
    while (!stop_.load() && !failed()) guarded([&] { write_batch(std::chrono::milliseconds(100)); });
  }

  // a disk error is kept (the first one) and ends the recording instead of the process
  template <typename F>
  void guarded(F&& f) {
    try {
      f();
    } catch (const std::exception& e) {
      if (!failed_.exchange(true)) error_ = e.what();
    }
  }

  void stop_disk() {
    stop_.store(true);
    disk_.join();
  }

  const RecordOptions& options_;
  FILE* log_;
  DiskQueue queue_;  // before the bus: its readers push until the bus is gone
  std::unique_ptr<bag::RecordingWriter> bag_;
  std::mutex bag_mutex_;  // the disk thread writes, the recording's thread adds topics
  GapCounter gaps_;
  std::vector<Received> batch_;
  std::atomic<bool> stop_{false};
  std::atomic<bool> failed_{false};
  std::string error_;
  std::unique_ptr<BusTap> tap_;
  std::thread disk_;
};

}  // namespace

void check_record_topics(const std::vector<std::string>& topics) {
  std::vector<std::string> known;
  for (const transport::KnownTopic& k : transport::known_topics()) known.push_back(k.name);
  for (const std::string& topic : topics) {
    if (in_family(topic) || std::find(known.begin(), known.end(), topic) != known.end()) continue;
    throw ConfigError("--topics " + topic + ": not a teleop topic" + did_you_mean(topic, known) +
                      " (`teleop topic list` shows the bus's topics)");
  }
}

RecordResult record(const BusOptions& bus_options, const RecordOptions& options, FILE* log) {
  check_record_topics(options.topics);
  const int64_t start_ns = monotonic_now_ns();
  Recording recording(bus_options, options, log);
  recording.subscribe_known_topics();
  while (!runtime::shutdown_requested() && !recording.failed()) {
    recording.subscribe_new_topics();
    if (options.duration_s > 0 && monotonic_now_ns() - start_ns >= static_cast<int64_t>(options.duration_s * 1e9))
      break;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  RecordResult result = recording.finish();
  result.seconds = static_cast<double>(monotonic_now_ns() - start_ns) * 1e-9;
  result.cpu_s = cpu_seconds();
  return result;
}

}  // namespace teleop::tools
