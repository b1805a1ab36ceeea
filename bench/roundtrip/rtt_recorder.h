#pragma once
// RTT bookkeeping, fed from a receive thread (the Fast DDS listener, or the raw UDP receiver)
// while the pinger's loop reads the counters.

#include <atomic>
#include <cstdint>
#include <mutex>
#include <vector>

#include "teleop/common/histogram.h"

namespace teleop::bench {

/// A window of `window_size` cycles of `topics` samples each (every topic carries the cycle's
/// sequence number).
class RttRecorder {
 public:
  RttRecorder(uint64_t window_size, int topics)
      : window_size_(window_size), topics_(static_cast<uint64_t>(topics)), rtt_ns_(window_size * topics_, -1) {}

  /// Called on the receive thread with the reply's topic index and sequence number, the
  /// pinger's monotonic stamp it carries, and the monotonic time of arrival.
  void on_reply(int topic, uint64_t seq, int64_t stamp_mono_ns, int64_t arrival_mono_ns) {
    replies_.fetch_add(1, std::memory_order_release);
    const uint64_t begin = window_begin_.load(std::memory_order_acquire);
    if (seq < begin || seq - begin >= window_size_) return;  // warm-up, or not ours to measure
    if (topic < 0 || static_cast<uint64_t>(topic) >= topics_) return;
    const int64_t rtt = arrival_mono_ns - stamp_mono_ns;
    std::lock_guard lock(mutex_);
    int64_t& slot = rtt_ns_[(seq - begin) * topics_ + static_cast<uint64_t>(topic)];
    if (slot >= 0) {
      ++duplicates_;
      return;
    }
    slot = rtt;
    histogram_.record(rtt);
    ++received_;
  }
  void on_stray() { stray_.fetch_add(1, std::memory_order_relaxed); }

  /// Replies of any sequence number seen so far (the echo is alive and answering).
  uint64_t replies() const { return replies_.load(std::memory_order_acquire); }
  /// From now on, sequence numbers [first_seq, first_seq + window) are measured.
  void open_window(uint64_t first_seq) { window_begin_.store(first_seq, std::memory_order_release); }
  uint64_t window_begin() const { return window_begin_.load(std::memory_order_acquire); }

  uint64_t received() const {
    std::lock_guard lock(mutex_);
    return received_;
  }

  uint64_t topics() const { return topics_; }

  struct Snapshot {
    DurationHistogram histogram;
    std::vector<int64_t> rtt_ns;  // per (cycle in the window) * topics + topic; -1 = no reply
    uint64_t received = 0;
    uint64_t duplicates = 0;
    uint64_t stray = 0;
  };
  Snapshot snapshot() const {
    std::lock_guard lock(mutex_);
    return {histogram_, rtt_ns_, received_, duplicates_, stray_.load(std::memory_order_relaxed)};
  }

 private:
  const uint64_t window_size_;
  const uint64_t topics_;
  std::atomic<uint64_t> window_begin_{UINT64_MAX};
  std::atomic<uint64_t> replies_{0};
  std::atomic<uint64_t> stray_{0};
  mutable std::mutex mutex_;
  DurationHistogram histogram_;
  std::vector<int64_t> rtt_ns_;
  uint64_t received_ = 0;
  uint64_t duplicates_ = 0;
};

}  // namespace teleop::bench
