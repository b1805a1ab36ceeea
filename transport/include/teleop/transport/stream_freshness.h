#pragma once
// Deadline and liveliness of a stream, checked by its reader from the arrival times of samples
// instead of by Fast DDS timers.
//
// Why: in Fast DDS 2.9 the DEADLINE QoS and MANUAL_BY_TOPIC liveliness re-arm a timer on every
// write and on every received sample, and each re-arm wakes the participant's timed-event thread:
// measured on the 1 kHz round trip (docs/benchmarks.md), about 8 futex calls per round trip
// instead of none, +50 % instructions, and the median round trip twice bare Fast DDS's. A stream
// is written every cycle, so "a sample arrived within the lease" is exactly what MANUAL_BY_TOPIC
// liveliness asserted, and "within the deadline" what the deadline checked; both are kept here
// as three numbers updated on arrival and evaluated when asked.
//
// The stream's liveliness is the stream's, not each writer's: alive (1) while samples arrive
// within the lease from a matched writer, a lapse counted once a lease passes without one. A
// writer that leaves cleanly (unmatched while samples still came) is no lapse, as in DDS.
// Deadline misses count every whole period without a sample since the last one, as Fast DDS's
// reader did; none before the first sample.
//
// Threads: the updates come from Fast DDS's listener threads (serialised among themselves by a
// spin flag), the queries from any thread (the control loop) without a lock: a sequence counter
// lets a query retry the rare read that overlapped an update.

#include <atomic>
#include <cstdint>

namespace teleop::transport {

class StreamFreshness {
 public:
  /// Setup time, before the reader exists: the liveliness lease and the deadline [ns], 0: none
  /// (no lapse, no miss). Not called: the reader is not a stream, DDS checks what its QoS asks.
  void configure(int64_t lease_ns, int64_t deadline_ns) {
    lease_ns_ = lease_ns > 0 ? lease_ns : INT64_MAX;
    deadline_ns_ = deadline_ns > 0 ? deadline_ns : 0;
    configured_ = true;
  }
  bool enabled() const { return configured_; }
  /// INT64_MAX: no lease.
  int64_t lease_ns() const { return lease_ns_; }
  /// 0: no deadline.
  int64_t deadline_ns() const { return deadline_ns_; }

  /// A sample arrived at `now_ns` (monotonic). Listener thread.
  void on_arrival(int64_t now_ns) {
    Update u(*this);
    const int64_t last = last_ns_.load(std::memory_order_relaxed);
    // two receive threads may report their arrivals out of order: time never runs back here
    if (now_ns <= last) return;
    if (last > 0) {
      const int64_t gap = now_ns - last;
      if (gap > lease_ns_) lapses_.store(lapses_.load(std::memory_order_relaxed) + 1, std::memory_order_relaxed);
      if (deadline_ns_ > 0) {
        missed_.store(missed_.load(std::memory_order_relaxed) + static_cast<uint64_t>(gap / deadline_ns_),
                      std::memory_order_relaxed);
      }
    }
    last_ns_.store(now_ns, std::memory_order_relaxed);
  }

  /// No writer is matched any more. Listener thread. A silence that had already lasted a lease
  /// stays counted; the stream then waits for its next first sample.
  void on_unmatched(int64_t now_ns) {
    Update u(*this);
    const State s{last_ns_.load(std::memory_order_relaxed), lapses_.load(std::memory_order_relaxed),
                  missed_.load(std::memory_order_relaxed)};
    lapses_.store(lapses_of(s, now_ns), std::memory_order_relaxed);
    missed_.store(missed_of(s, now_ns), std::memory_order_relaxed);
    last_ns_.store(0, std::memory_order_relaxed);
  }

  /// 1 while a matched writer's last sample is less than a lease old, else 0.
  int32_t alive(int64_t now_ns, int32_t matched) const {
    const int64_t last = read().last_ns;
    return matched > 0 && last > 0 && now_ns - last <= lease_ns_ ? 1 : 0;
  }
  /// Lapses so far, the one going on included.
  uint64_t lapses(int64_t now_ns) const { return lapses_of(read(), now_ns); }
  /// Whole deadline periods without a sample so far, the running silence included.
  uint64_t deadline_missed(int64_t now_ns) const { return missed_of(read(), now_ns); }

 private:
  struct State {
    int64_t last_ns;  // 0: no sample since the start or since the last writer left
    uint64_t lapses;
    uint64_t missed;
  };

  // one update at a time; the sequence counter is odd while it runs
  struct Update {
    explicit Update(StreamFreshness& f) : f_(f) {
      while (f_.updating_.test_and_set(std::memory_order_acquire)) {
      }
      f_.seq_.store(f_.seq_.load(std::memory_order_relaxed) + 1, std::memory_order_relaxed);
      std::atomic_thread_fence(std::memory_order_release);
    }
    ~Update() {
      f_.seq_.store(f_.seq_.load(std::memory_order_relaxed) + 1, std::memory_order_release);
      f_.updating_.clear(std::memory_order_release);
    }
    Update(const Update&) = delete;
    Update& operator=(const Update&) = delete;
    StreamFreshness& f_;
  };

  State read() const {
    while (true) {
      const uint32_t before = seq_.load(std::memory_order_acquire);
      const State s{last_ns_.load(std::memory_order_relaxed), lapses_.load(std::memory_order_relaxed),
                    missed_.load(std::memory_order_relaxed)};
      std::atomic_thread_fence(std::memory_order_acquire);
      if ((before & 1U) == 0 && seq_.load(std::memory_order_relaxed) == before) return s;
    }
  }

  uint64_t lapses_of(const State& s, int64_t now_ns) const {
    return s.lapses + (s.last_ns > 0 && now_ns - s.last_ns > lease_ns_ ? 1 : 0);
  }
  uint64_t missed_of(const State& s, int64_t now_ns) const {
    if (s.last_ns <= 0 || deadline_ns_ <= 0 || now_ns <= s.last_ns) return s.missed;
    return s.missed + static_cast<uint64_t>((now_ns - s.last_ns) / deadline_ns_);
  }

  bool configured_ = false;
  int64_t lease_ns_ = INT64_MAX;
  int64_t deadline_ns_ = 0;
  std::atomic_flag updating_ = ATOMIC_FLAG_INIT;
  std::atomic<uint32_t> seq_{0};
  std::atomic<int64_t> last_ns_{0};
  std::atomic<uint64_t> lapses_{0};
  std::atomic<uint64_t> missed_{0};
};

}  // namespace teleop::transport
