#pragma once
// Lock-free view of an endpoint's DDS status, updated by Fast DDS listener threads and read by
// the control loop without taking any lock.

#include <atomic>
#include <cstdint>

namespace teleop::transport {

struct EndpointStatus {
  /// Remote endpoints currently matched.
  std::atomic<int32_t> matched{0};
  /// Remote writers whose liveliness lease is alive (readers only).
  std::atomic<int32_t> alive{0};
  /// Writers that lost liveliness since start (readers only).
  std::atomic<uint64_t> liveliness_lost{0};
  /// Deadline periods without a sample (readers: requested, writers: offered).
  std::atomic<uint64_t> deadline_missed{0};
};

}  // namespace teleop::transport
