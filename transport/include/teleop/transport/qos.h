#pragma once
// Named QoS presets: every topic uses one of them, so that behaviour is uniform and reviewed once.

#include <fastdds/dds/publisher/qos/DataWriterQos.hpp>
#include <fastdds/dds/subscriber/qos/DataReaderQos.hpp>

#include "teleop/transport/participant_config.h"

namespace teleop::transport {

enum class QosPreset {
  /// 1 kHz streams (states, commands, feedback): best effort, keep-last 1. A lost sample is
  /// superseded by the next one one period later; retransmitting it would only add latency.
  /// Deadline and liveliness are checked by the reader from arrivals (stream_freshness.h), not
  /// by DDS, whose timers cost a wake-up per sample.
  kStream,
  /// Low-rate state that late joiners need (node status, configuration): reliable, writer
  /// keep-last 1, transient-local, so a reader that starts late still gets the last value.
  kState,
  /// Discrete events that must all arrive in order (mode switches, clutch, hand enable):
  /// reliable, keep-all (bounded), volatile, with fast heartbeats so a loss is repaired within
  /// tens of milliseconds.
  kEvent,
};

/// Samples an event writer holds until acknowledged before write() blocks.
constexpr int32_t kEventQueueDepth = 1024;

/// Samples a reader keeps between two polls of its loop (every preset).
constexpr int32_t kReaderDepth = 16;

const char* to_string(QosPreset preset);

/// A duration in ns as DDS wants it.
eprosima::fastrtps::Duration_t to_dds_duration(int64_t ns);

/// Writer QoS of a preset. The state and event presets carry automatic liveliness with the
/// configured lease, so readers notice a dead peer (streams: their readers, see kStream); every
/// preset has data-sharing off so that all traffic goes through the configured transports
/// (where it can be observed and impaired).
eprosima::fastdds::dds::DataWriterQos writer_qos(QosPreset preset, const ParticipantConfig& config);
eprosima::fastdds::dds::DataReaderQos reader_qos(QosPreset preset, const ParticipantConfig& config);

}  // namespace teleop::transport
