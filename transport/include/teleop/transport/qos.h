#pragma once
// Named QoS presets: every topic uses one of them, so that behaviour is uniform and reviewed once.
// The nodes run with these presets as Fast DDS XML profiles (config/qos/teleop_profiles.xml,
// qos_profiles.h), which a user can replace; the functions here are the reference that the shipped
// profiles reproduce field by field (transport_qos_profiles_test).

#include <fastdds/dds/domain/qos/DomainParticipantQos.hpp>
#include <fastdds/dds/publisher/qos/DataWriterQos.hpp>
#include <fastdds/dds/subscriber/qos/DataReaderQos.hpp>

#include "teleop/transport/participant_config.h"

namespace teleop::transport {

enum class QosPreset {
  /// 1 kHz streams (states, commands, feedback): best effort, keep-last 1, deadline. A lost
  /// sample is superseded by the next one one period later; retransmitting it would only add
  /// latency. The deadline and the liveliness lease are checked by the reader from arrivals
  /// (stream_freshness.h), not by DDS, whose timers cost a wake-up per sample.
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

/// The presets' liveliness lease, participant lease and stream deadline where the node's YAML
/// does not set them (`liveliness_lease_ms`, `participant_lease_ms`, `stream_deadline_ms`).
constexpr int64_t kDefaultLivelinessLeaseNs = 250'000'000;
constexpr int64_t kDefaultParticipantLeaseNs = 3'000'000'000;
constexpr int64_t kDefaultStreamDeadlineNs = 5'000'000;

const char* to_string(QosPreset preset);

/// A duration in ns as DDS wants it.
eprosima::fastrtps::Duration_t to_dds_duration(int64_t ns);

/// Writer QoS of a preset. Every preset carries liveliness with the configured lease, so readers
/// notice a dead peer (a stream's is checked by its readers, see kStream), and has data-sharing
/// off so that all traffic goes through the configured transports (where it can be observed and
/// impaired).
eprosima::fastdds::dds::DataWriterQos writer_qos(QosPreset preset, const ParticipantConfig& config);
eprosima::fastdds::dds::DataReaderQos reader_qos(QosPreset preset, const ParticipantConfig& config);

/// A stream's deadline and liveliness lease as its QoS (profile and YAML) names them [ns]; 0: none.
/// Its readers check both from the arrivals of samples (StreamFreshness), not DDS: Fast DDS 2.9
/// re-arms a timer and wakes its event thread per sample for each (docs/benchmarks.md).
struct StreamChecks {
  int64_t lease_ns = 0;
  int64_t deadline_ns = 0;
};
StreamChecks stream_checks(const eprosima::fastdds::dds::DataReaderQos& qos);

/// What a stream endpoint is created with: its QoS without the DDS deadline and liveliness
/// (automatic, infinite lease, no announcements), which stream_checks() hands to the reader.
eprosima::fastdds::dds::DataWriterQos without_dds_timers(eprosima::fastdds::dds::DataWriterQos qos);
eprosima::fastdds::dds::DataReaderQos without_dds_timers(eprosima::fastdds::dds::DataReaderQos qos);

/// The participant QoS the presets set: its lease, announced three times per lease. Everything
/// else of a participant (name, transports, discovery, security) follows its YAML (participant.cpp).
eprosima::fastdds::dds::DomainParticipantQos participant_qos_preset(const ParticipantConfig& config);

/// The node's YAML overrides (`liveliness_lease_ms`, `stream_deadline_ms`, `participant_lease_ms`),
/// applied to a QoS of `preset` wherever it came from (a preset or a profiles file).
void apply_overrides(eprosima::fastdds::dds::DataWriterQos& qos, QosPreset preset, const ParticipantConfig& config);
void apply_overrides(eprosima::fastdds::dds::DataReaderQos& qos, QosPreset preset, const ParticipantConfig& config);
void apply_overrides(eprosima::fastdds::dds::DomainParticipantQos& qos, const ParticipantConfig& config);

}  // namespace teleop::transport
