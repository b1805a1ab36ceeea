#pragma once
// Samples as their serialized bytes: CDR with its 4-byte encapsulation header, exactly as on the
// wire. Tools that handle every type alike (record, replay, echo) read and write these; the typed
// Reader/Writer stay what nodes use.

#include <fastdds/dds/publisher/DataWriter.hpp>

#include <cstdint>
#include <functional>
#include <vector>

#include "teleop/common/stream_session.h"
#include "teleop/transport/endpoint_status.h"

namespace teleop::transport {

struct RawSample {
  std::vector<uint8_t> cdr;
  /// When DDS received it, CLOCK_REALTIME ns.
  int64_t reception_ns = 0;
  WriterId writer;
};

/// Receives each raw sample on a Fast DDS thread.
using RawSampleCallback = std::function<void(const RawSample&)>;

/// A non-owning handle to a writer of serialized samples. The Participant owns the entity.
class RawWriter {
 public:
  RawWriter() = default;
  RawWriter(eprosima::fastdds::dds::DataWriter* writer, const EndpointStatus* status)
      : writer_(writer), status_(status) {}

  /// Sends the bytes as one sample of the writer's type. False when DDS refused it.
  [[nodiscard]] bool write(const std::vector<uint8_t>& cdr) {
    // Fast DDS 2.9 takes a non-const pointer; the raw type only reads it
    return writer_->write(const_cast<std::vector<uint8_t>*>(&cdr));
  }
  int32_t matched() const { return status_->matched.load(std::memory_order_relaxed); }
  bool valid() const { return writer_ != nullptr; }

 private:
  eprosima::fastdds::dds::DataWriter* writer_ = nullptr;
  const EndpointStatus* status_ = nullptr;
};

}  // namespace teleop::transport
