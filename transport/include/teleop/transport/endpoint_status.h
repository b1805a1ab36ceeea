#pragma once
// Lock-free view of an endpoint's DDS status, updated by Fast DDS listener threads and read by
// the control loop without taking any lock.

#include <array>
#include <atomic>
#include <cstdint>

#include "teleop/common/fixed_text.h"
#include "teleop/transport/stream_freshness.h"

namespace teleop::transport {

/// Whom a reader's flow follows and what it refused, by cause (index: msg::REFUSAL_*). Written
/// by the node's loop (Subscription) and read on the same thread by its status publisher: plain
/// fields, no other thread reads them.
struct FlowAuthority {
  /// The followed writer's node (SampleHeader.source); empty before the first sample.
  FixedText<32> following;
  /// The followed writer's GUID, in hex (WriterId::hex).
  FixedText<33> following_writer;
  /// Whether the followed writer's newest sample is in force (taken, and valid for the node).
  bool in_force = false;
  std::array<uint64_t, 5> refused{};
  /// The last refusal: the writer's node, its cause (msg::REFUSAL_*) and the node's reason.
  FixedText<32> refused_source;
  uint32_t refusal = 0;
  FixedText<32> refusal_detail;
};

struct EndpointStatus {
  /// Remote endpoints currently matched.
  std::atomic<int32_t> matched{0};
  /// Remote writers whose liveliness lease is alive (readers only; DDS's count, not streams').
  std::atomic<int32_t> alive{0};
  /// Writers that lost liveliness since start (readers only; DDS's count, not streams').
  std::atomic<uint64_t> liveliness_lost{0};
  /// Deadline periods without a sample (DDS's count: writers; readers of QoS with a deadline).
  std::atomic<uint64_t> deadline_missed{0};
  /// A stream reader's deadline and liveliness, checked on arrival instead of by DDS timers.
  StreamFreshness freshness;

  // What the node made of a reader's flow (readers only), for NodeStatus and the tools.
  /// Whether the node needs a writer on this flow to do its work (a reader of an optional or
  /// alternative input is not awaited: nobody is told it waits for one).
  std::atomic<bool> awaited{false};
  /// When DDS last had data for the reader (CLOCK_MONOTONIC ns, 0: never): a Fast DDS thread sets it.
  std::atomic<int64_t> last_data_mono_ns{0};
  /// Samples the node took, and the gaps in their sequence numbers within sessions (Subscription).
  std::atomic<uint64_t> received{0};
  std::atomic<uint64_t> lost{0};
  /// One-way latency (source stamp to reception, CLOCK_REALTIME) smoothed over ~64 samples [ns].
  std::atomic<int64_t> latency_ns{0};
  /// The followed writer's clock against ours (common/clock_offset.h) [ns].
  std::atomic<int64_t> clock_offset_ns{0};
  /// Who the flow follows, what it refused (readers taken through a Subscription).
  FlowAuthority authority;
};

}  // namespace teleop::transport
