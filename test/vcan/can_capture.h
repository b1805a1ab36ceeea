#pragma once
// An independent observer of CAN buses for the HIL tests: every frame of several interfaces with
// the kernel's receive timestamp, captured by a thread of its own, and what the tests ask of the
// capture (the CANopen services by COB-ID, the SYNCs between two instants, the bits on the wire).

#include <poll.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "teleop/can/bus_load.h"
#include "teleop/can/cia301.h"
#include "teleop/can/socketcan_bus.h"

namespace teleop::can::test {

struct CapturedFrame {
  size_t bus = 0;     // index into the interfaces given
  CanFrame frame;
  int64_t t_ns = 0;   // kernel receive timestamp (CLOCK_REALTIME)
  ServiceId service;  // by COB-ID
};

class CanCapture {
 public:
  explicit CanCapture(const std::vector<std::string>& interfaces) {
    SocketCanOptions options;
    options.receive_buffer_bytes = 4 << 20;  // a starved test thread must not lose frames
    for (const std::string& name : interfaces) buses_.push_back(std::make_unique<SocketCanBus>(name, options));
    thread_ = std::thread([this] { run(); });
  }
  ~CanCapture() {
    stop_ = true;
    thread_.join();
  }
  CanCapture(const CanCapture&) = delete;
  CanCapture& operator=(const CanCapture&) = delete;

  /// Every frame captured so far, in the order each bus received them.
  std::vector<CapturedFrame> frames() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return frames_;
  }
  /// The newest frame of `service` from/to `node` on `bus` (no copy of the capture); false when none.
  bool latest(size_t bus, Service service, NodeId node, CapturedFrame& out) const {
    std::lock_guard<std::mutex> lock(mutex_);
    for (auto it = frames_.rbegin(); it != frames_.rend(); ++it) {
      if (it->bus == bus && it->service.service == service && it->service.node == node) {
        out = *it;
        return true;
      }
    }
    return false;
  }
  /// Frames the kernel dropped for this observer (its socket's queue overflowed).
  uint64_t overruns() const {
    uint64_t n = 0;
    for (const auto& b : buses_) n += b->stats().rx_overruns;
    return n;
  }

 private:
  void run() {
    std::vector<pollfd> fds;
    for (const auto& b : buses_) fds.push_back({b->fd(), POLLIN, 0});
    while (!stop_) {
      ::poll(fds.data(), fds.size(), 10);
      for (size_t i = 0; i < buses_.size(); ++i) {
        CanFrame f;
        int64_t t = 0;
        while (buses_[i]->receive(f, std::chrono::nanoseconds(0), t) == CanStatus::kOk) {
          std::lock_guard<std::mutex> lock(mutex_);
          frames_.push_back({i, f, t, classify(f)});
        }
      }
    }
  }

  std::vector<std::unique_ptr<SocketCanBus>> buses_;
  std::thread thread_;
  std::atomic<bool> stop_{false};
  mutable std::mutex mutex_;
  std::vector<CapturedFrame> frames_;
};

inline bool is(const CapturedFrame& c, size_t bus, Service service, NodeId node = 0) {
  return c.bus == bus && c.service.service == service && (node == 0 || c.service.node == node);
}

/// Frames of `service` (from/to `node`, 0: any) on `bus` with from_ns < t <= to_ns.
inline size_t count_between(const std::vector<CapturedFrame>& frames, size_t bus, Service service, NodeId node,
                            int64_t from_ns, int64_t to_ns) {
  return static_cast<size_t>(std::count_if(frames.begin(), frames.end(), [&](const CapturedFrame& c) {
    return is(c, bus, service, node) && c.t_ns > from_ns && c.t_ns <= to_ns;
  }));
}

/// SYNCs on `bus` with from_ns < t <= to_ns.
inline size_t syncs_between(const std::vector<CapturedFrame>& frames, size_t bus, int64_t from_ns, int64_t to_ns) {
  return count_between(frames, bus, Service::kSync, 0, from_ns, to_ns);
}

/// What one bus carried between two instants: frames, SYNCs and the bits on the wire (the
/// arithmetic of bus_load.h, each frame by its own length).
struct MeasuredLoad {
  int64_t from_ns = 0;  // the first SYNC of the window
  int64_t to_ns = 0;    // the last one (not counted)
  size_t frames = 0;
  size_t syncs = 0;
  double seconds = 0.0;
  double bits_nominal = 0.0;
  double bits_worst_case = 0.0;
  double bits_per_s_nominal() const { return bits_nominal / seconds; }
  double bits_per_s_worst_case() const { return bits_worst_case / seconds; }
  double sync_rate_hz() const { return static_cast<double>(syncs) / seconds; }
};

/// The load of `bus` from its first SYNC after from_ns to its last SYNC before to_ns (whole SYNC
/// cycles, so that the cyclic traffic is counted completely).
inline MeasuredLoad measure_load(const std::vector<CapturedFrame>& frames, size_t bus, int64_t from_ns, int64_t to_ns) {
  int64_t first = -1, last = -1;
  for (const CapturedFrame& c : frames) {
    if (!is(c, bus, Service::kSync) || c.t_ns <= from_ns || c.t_ns > to_ns) continue;
    if (first < 0) first = c.t_ns;
    last = c.t_ns;
  }
  MeasuredLoad m;
  if (first < 0 || last <= first) return m;
  for (const CapturedFrame& c : frames) {
    if (c.bus != bus || c.t_ns < first || c.t_ns >= last || c.frame.error()) continue;
    const CanIdFormat format = c.frame.extended() ? CanIdFormat::kExtended : CanIdFormat::kStandard;
    ++m.frames;
    m.syncs += c.service.service == Service::kSync ? 1 : 0;
    m.bits_nominal += frame_bits_nominal(c.frame.dlc, format);
    m.bits_worst_case += frame_bits_worst_case(c.frame.dlc, format);
  }
  m.from_ns = first;
  m.to_ns = last;
  m.seconds = static_cast<double>(last - first) * 1e-9;
  return m;
}

}  // namespace teleop::can::test
