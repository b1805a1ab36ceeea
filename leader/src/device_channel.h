#pragma once
// The shared memory between the leader and the process that hosts its device plugin
// (teleop_device_host, leader.plugin.isolation: process): the device's newest state one way, the
// newest feedback the other, each under a sequence lock (the writer makes its count odd while it
// writes; a reader that saw it odd or changed retries, a bounded number of times), and the host's
// heartbeat, so that the leader tells a host that died (a vendor SDK that crashed) from a slow one.
// Lock-free on both sides: the leader's control thread never waits for the host.

#include <atomic>
#include <cstdint>
#include <cstring>

#include "teleop/leader/leader_device.h"

namespace teleop::leader {

/// One value under a sequence lock, shared between two processes (T trivially copyable).
template <typename T>
struct SeqLocked {
  std::atomic<uint32_t> sequence{0};
  T value{};

  /// The one writer.
  void store(const T& v) {
    const uint32_t s = sequence.load(std::memory_order_relaxed);
    sequence.store(s + 1, std::memory_order_relaxed);
    std::atomic_thread_fence(std::memory_order_release);
    std::memcpy(static_cast<void*>(&value), &v, sizeof v);
    sequence.store(s + 2, std::memory_order_release);
  }
  /// False when every try met a write under way (the reader keeps what it had).
  bool load(T& out, int tries = 4) const {
    for (int i = 0; i < tries; ++i) {
      const uint32_t before = sequence.load(std::memory_order_acquire);
      if (before % 2 != 0) continue;
      T copy;
      std::memcpy(static_cast<void*>(&copy), &value, sizeof copy);
      std::atomic_thread_fence(std::memory_order_acquire);
      if (sequence.load(std::memory_order_relaxed) == before) {
        out = copy;
        return true;
      }
    }
    return false;
  }
};

/// What the host measured in its last cycle.
struct HostedState {
  DeviceState state;
  uint32_t read_ok = 0;  // the plugin's read succeeded (and was finite)
};

struct DeviceChannel {
  enum Phase : uint32_t { kOpening = 0, kOpen = 1, kFailed = 2 };

  std::atomic<uint32_t> phase{kOpening};
  // set by the host before it says kOpen
  uint32_t joints = 0;
  char name[64] = {};
  char error[256] = {};  // why it failed to open (kFailed)
  // the host's CLOCK_MONOTONIC at its last cycle [ns]
  std::atomic<int64_t> heartbeat_ns{0};
  SeqLocked<HostedState> state;
  SeqLocked<JointVector> feedback;
  // the plugin's counters, as the host's PluginDevice keeps them
  std::atomic<uint64_t> failed_reads{0};
  std::atomic<uint64_t> invalid_reads{0};
  std::atomic<uint64_t> failed_writes{0};
  std::atomic<uint64_t> limited_efforts{0};
};

static_assert(std::atomic<int64_t>::is_always_lock_free && std::atomic<uint32_t>::is_always_lock_free,
              "the channel's atomics work across processes only when lock-free");

}  // namespace teleop::leader
