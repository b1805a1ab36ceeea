#pragma once
// Typed, non-owning handle to a DDS writer. The Participant owns the entity and outlives it.

#include <fastdds/dds/publisher/DataWriter.hpp>

#include <cstring>

#include "teleop/common/stream_session.h"
#include "teleop/transport/endpoint_status.h"

namespace teleop::transport {

template <typename T>
class Writer {
 public:
  Writer() = default;
  Writer(eprosima::fastdds::dds::DataWriter* writer, const EndpointStatus* status) : writer_(writer), status_(status) {}

  /// Sends one sample. Real-time safe for the stream preset (best effort, preallocated
  /// payloads, synchronous UDP send). Returns false if DDS refused the sample.
  [[nodiscard]] bool write(const T& sample) {
    // Fast DDS 2.9 takes a non-const pointer but does not modify the sample
    return writer_->write(const_cast<T*>(&sample));
  }

  /// Blocks up to `timeout_ns` until reliable readers acknowledged everything written.
  /// Not for the loop: for a last sample before shutdown. Returns false on timeout.
  bool wait_for_acknowledgments(int64_t timeout_ns) {
    const eprosima::fastrtps::Duration_t timeout(static_cast<int32_t>(timeout_ns / 1'000'000'000),
                                                 static_cast<uint32_t>(timeout_ns % 1'000'000'000));
    return writer_->wait_for_acknowledgments(timeout) == eprosima::fastrtps::types::ReturnCode_t::RETCODE_OK;
  }

  /// Readers currently matched.
  int32_t matched() const { return status_->matched.load(std::memory_order_relaxed); }
  uint64_t deadline_missed() const { return status_->deadline_missed.load(std::memory_order_relaxed); }
  bool valid() const { return writer_ != nullptr; }
  /// The writer's GUID, as its readers know it (Reader::take_next's WriterId).
  WriterId id() const {
    WriterId id;
    const auto guid = writer_->guid();
    std::memcpy(id.bytes.data(), guid.guidPrefix.value, 12);
    std::memcpy(id.bytes.data() + 12, guid.entityId.value, 4);
    return id;
  }

 private:
  eprosima::fastdds::dds::DataWriter* writer_ = nullptr;
  const EndpointStatus* status_ = nullptr;
};

}  // namespace teleop::transport
