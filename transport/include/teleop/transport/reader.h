#pragma once
// Typed, non-owning handle to a DDS reader. The Participant owns the entity and outlives it.

#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>

#include <cstring>

#include "teleop/common/clock.h"
#include "teleop/common/stream_session.h"
#include "teleop/transport/endpoint_status.h"

namespace teleop::transport {

template <typename T>
class Reader {
 public:
  Reader() = default;
  Reader(eprosima::fastdds::dds::DataReader* reader, EndpointStatus* status) : reader_(reader), status_(status) {}

  /// Non-blocking: moves the oldest unread sample into `out`, the time DDS received it
  /// (CLOCK_REALTIME ns) into `reception_ns` and the DataWriter that wrote it into `writer`.
  /// Returns false when there is none. Does not allocate once `out`'s sequences have reached
  /// their working size.
  [[nodiscard]] bool take_next(T& out, int64_t& reception_ns, WriterId& writer) {
    eprosima::fastdds::dds::SampleInfo info;
    while (reader_->take_next_sample(&out, &info) == eprosima::fastrtps::types::ReturnCode_t::RETCODE_OK) {
      // skip state-only notifications (e.g. a writer's disposal) that carry no data
      if (info.valid_data) {
        // on the clock this process stamps with (common/clock.h)
        reception_ns = info.reception_timestamp.to_ns() + realtime_offset_ns();
        // the publication handle is the writer's GUID
        const eprosima::fastrtps::rtps::octet* guid = info.publication_handle.value;
        std::memcpy(writer.bytes.data(), guid, writer.bytes.size());
        return true;
      }
    }
    return false;
  }

  [[nodiscard]] bool take_next(T& out) {
    int64_t ignored = 0;
    WriterId writer;
    return take_next(out, ignored, writer);
  }

  /// Blocks until an unread sample is there (true) or `timeout_ns` passed (false). For lock-step
  /// exchanges, which block by design; never in a paced loop.
  bool wait_for_data(int64_t timeout_ns) {
    const int64_t s = timeout_ns / 1'000'000'000;
    const eprosima::fastrtps::Duration_t timeout(static_cast<int32_t>(s), static_cast<uint32_t>(timeout_ns - s * 1'000'000'000));
    return reader_->wait_for_unread_message(timeout);
  }

  int32_t matched() const { return status_->matched.load(std::memory_order_relaxed); }
  /// Remote writers whose liveliness is currently asserted. A stream's (StreamFreshness): 1
  /// while samples arrive within the lease, else 0. Real-time safe.
  int32_t alive_writers() const {
    const StreamFreshness& f = status_->freshness;
    return f.enabled() ? f.alive(monotonic_now_ns(), matched()) : status_->alive.load(std::memory_order_relaxed);
  }
  /// Lapses of liveliness so far (a stream's: leases without a sample, the running one included).
  uint64_t liveliness_lost() const {
    const StreamFreshness& f = status_->freshness;
    return f.enabled() ? f.lapses(monotonic_now_ns()) : status_->liveliness_lost.load(std::memory_order_relaxed);
  }
  /// Deadline periods without a sample so far (a stream's: the running silence included).
  uint64_t deadline_missed() const {
    const StreamFreshness& f = status_->freshness;
    return f.enabled() ? f.deadline_missed(monotonic_now_ns()) : status_->deadline_missed.load(std::memory_order_relaxed);
  }
  /// The liveliness lease this reader requests of its writers (a stream's: checked by the reader).
  int64_t liveliness_lease_ns() const {
    if (status_->freshness.enabled()) return status_->freshness.lease_ns();
    const auto& lease = reader_->get_qos().liveliness().lease_duration;
    return static_cast<int64_t>(lease.seconds) * 1'000'000'000 + static_cast<int64_t>(lease.nanosec);
  }
  /// The requested deadline (what the QoS profiles and the YAML made it); 0: none. A stream's
  /// is checked by the reader (StreamFreshness), not requested from DDS.
  int64_t deadline_ns() const {
    if (status_->freshness.enabled()) return status_->freshness.deadline_ns();
    const auto& period = reader_->get_qos().deadline().period;
    if (period == eprosima::fastrtps::c_TimeInfinite) return 0;
    return static_cast<int64_t>(period.seconds) * 1'000'000'000 + static_cast<int64_t>(period.nanosec);
  }
  bool valid() const { return reader_ != nullptr; }

  /// Whom the flow follows and what it refused (Subscription). The loop's thread only.
  FlowAuthority& authority() { return status_->authority; }
  const FlowAuthority& authority() const { return status_->authority; }

  /// Whether the node needs a writer on this flow (EndpointStatus::awaited). Setup time.
  void set_awaited(bool awaited) { status_->awaited.store(awaited, std::memory_order_relaxed); }

  /// Publishes what the node made of the flow (received, lost, smoothed latency) for NodeStatus
  /// and the tools. Real-time safe (relaxed atomic stores).
  void report_flow(uint64_t received, uint64_t lost, int64_t latency_ns, int64_t clock_offset_ns) {
    status_->clock_offset_ns.store(clock_offset_ns, std::memory_order_relaxed);
    status_->received.store(received, std::memory_order_relaxed);
    status_->lost.store(lost, std::memory_order_relaxed);
    status_->latency_ns.store(latency_ns, std::memory_order_relaxed);
  }

 private:
  eprosima::fastdds::dds::DataReader* reader_ = nullptr;
  EndpointStatus* status_ = nullptr;
};

}  // namespace teleop::transport
