#include "teleop/transport/qos.h"

namespace teleop::transport {
namespace dds = eprosima::fastdds::dds;
using eprosima::fastrtps::Duration_t;

Duration_t to_dds_duration(int64_t ns) {
  return Duration_t(static_cast<int32_t>(ns / 1'000'000'000), static_cast<uint32_t>(ns % 1'000'000'000));
}

namespace {

// the parts that writers and readers share
template <typename Qos>
void apply_common(Qos& qos, QosPreset preset) {
  qos.history().kind = dds::KEEP_LAST_HISTORY_QOS;
  qos.history().depth = 1;
  qos.liveliness().kind = dds::AUTOMATIC_LIVELINESS_QOS;
  qos.liveliness().lease_duration = to_dds_duration(kDefaultLivelinessLeaseNs);
  qos.data_sharing().off();
  // payloads preallocated at their bounded maximum: no allocation per sample
  qos.endpoint().history_memory_policy = eprosima::fastrtps::rtps::PREALLOCATED_WITH_REALLOC_MEMORY_MODE;
  switch (preset) {
    case QosPreset::kStream:
      // streams are written every cycle, so every write asserts the writer's liveliness. Not
      // AUTOMATIC: in Fast DDS 2.9 a reader keeps every automatic writer alive as long as any
      // participant asserts automatic liveliness (eProsima/Fast-DDS#4373, fixed in 2.10+), so
      // with three nodes a cut host was never noticed (measured in test/netns)
      qos.liveliness().kind = dds::MANUAL_BY_TOPIC_LIVELINESS_QOS;
      qos.reliability().kind = dds::BEST_EFFORT_RELIABILITY_QOS;
      qos.durability().kind = dds::VOLATILE_DURABILITY_QOS;
      qos.deadline().period = to_dds_duration(kDefaultStreamDeadlineNs);
      break;
    case QosPreset::kState:
      qos.reliability().kind = dds::RELIABLE_RELIABILITY_QOS;
      qos.durability().kind = dds::TRANSIENT_LOCAL_DURABILITY_QOS;
      break;
    case QosPreset::kEvent:
      qos.reliability().kind = dds::RELIABLE_RELIABILITY_QOS;
      qos.durability().kind = dds::VOLATILE_DURABILITY_QOS;
      qos.history().kind = dds::KEEP_ALL_HISTORY_QOS;
      qos.history().depth = kEventQueueDepth;
      break;
  }
}

}  // namespace

const char* to_string(QosPreset preset) {
  switch (preset) {
    case QosPreset::kStream: return "stream";
    case QosPreset::kState: return "state";
    case QosPreset::kEvent: return "event";
  }
  return "?";
}

dds::DataWriterQos writer_qos(QosPreset preset, const ParticipantConfig& config) {
  dds::DataWriterQos qos = dds::DATAWRITER_QOS_DEFAULT;
  apply_common(qos, preset);
  // assert liveliness three times per lease so one lost announcement is not a death
  qos.liveliness().announcement_period = to_dds_duration(kDefaultLivelinessLeaseNs / 3);
  // sending from the control thread itself: one sendto() per sample, no extra hand-off
  qos.publish_mode().kind = dds::SYNCHRONOUS_PUBLISH_MODE;
  if (preset == QosPreset::kState || preset == QosPreset::kEvent) {
    // the 3 s default would leave a lost sample unrepaired for seconds
    qos.reliable_writer_qos().times.heartbeatPeriod =
        to_dds_duration(preset == QosPreset::kEvent ? 20'000'000 : 100'000'000);
    // a reliable write never blocks the loop for long when the history is full
    qos.reliability().max_blocking_time = to_dds_duration(100'000);
  }
  if (preset == QosPreset::kEvent) {
    qos.resource_limits().max_instances = 1;
    qos.resource_limits().max_samples_per_instance = kEventQueueDepth;
    qos.resource_limits().max_samples = kEventQueueDepth;
  }
  apply_overrides(qos, preset, config);
  return qos;
}

dds::DataReaderQos reader_qos(QosPreset preset, const ParticipantConfig& config) {
  dds::DataReaderQos qos = dds::DATAREADER_QOS_DEFAULT;
  apply_common(qos, preset);
  // readers are drained periodically: with unsynchronised loops two stream samples can arrive
  // between two polls, and several nodes write the one (unkeyed) status topic; a depth of 1
  // would silently overwrite (and hide) samples. Writers keep 1: late joiners get the last.
  qos.history().depth = preset == QosPreset::kEvent ? kEventQueueDepth : kReaderDepth;
  // preallocate exactly the history, nothing grows at run time
  qos.resource_limits().max_instances = 1;
  qos.resource_limits().max_samples_per_instance = qos.history().depth;
  qos.resource_limits().max_samples = qos.history().depth;
  qos.resource_limits().allocated_samples = qos.history().depth;
  apply_overrides(qos, preset, config);
  return qos;
}

dds::DomainParticipantQos participant_qos_preset(const ParticipantConfig& config) {
  dds::DomainParticipantQos qos = dds::PARTICIPANT_QOS_DEFAULT;
  auto& discovery = qos.wire_protocol().builtin.discovery_config;
  discovery.leaseDuration = to_dds_duration(kDefaultParticipantLeaseNs);
  discovery.leaseDuration_announcementperiod = to_dds_duration(kDefaultParticipantLeaseNs / 3);
  apply_overrides(qos, config);
  return qos;
}

namespace {

// what both endpoint kinds take from the YAML
template <typename Qos>
void apply_endpoint_overrides(Qos& qos, QosPreset preset, const ParticipantConfig& config) {
  if (config.liveliness_lease_ns) qos.liveliness().lease_duration = to_dds_duration(*config.liveliness_lease_ns);
  if (preset == QosPreset::kStream && config.stream_deadline_ns) {
    qos.deadline().period = to_dds_duration(*config.stream_deadline_ns);
  }
  // whatever a profiles file says: impaired traffic must all pass the impairing transport
  if (config.impairment.enabled()) qos.data_sharing().off();
}

}  // namespace

void apply_overrides(dds::DataWriterQos& qos, QosPreset preset, const ParticipantConfig& config) {
  apply_endpoint_overrides(qos, preset, config);
  // three assertions per lease, as the presets
  if (config.liveliness_lease_ns) {
    qos.liveliness().announcement_period = to_dds_duration(*config.liveliness_lease_ns / 3);
  }
}

void apply_overrides(dds::DataReaderQos& qos, QosPreset preset, const ParticipantConfig& config) {
  apply_endpoint_overrides(qos, preset, config);
}

namespace {

// spelled out, not c_TimeInfinite: that is a per-file constant, still zero when a static
// initializer elsewhere creates an endpoint before this file's (participant_test's helper)
Duration_t infinite() { return Duration_t(Duration_t::INFINITE_SECONDS, Duration_t::INFINITE_NANOSECONDS); }

int64_t ns_or_none(const Duration_t& d) {
  if (d == infinite()) return 0;
  return static_cast<int64_t>(d.seconds) * 1'000'000'000 + static_cast<int64_t>(d.nanosec);
}

template <typename Qos>
Qos without_timers(Qos qos) {
  qos.deadline().period = infinite();
  qos.liveliness().kind = dds::AUTOMATIC_LIVELINESS_QOS;
  qos.liveliness().lease_duration = infinite();
  qos.liveliness().announcement_period = infinite();
  return qos;
}

}  // namespace

StreamChecks stream_checks(const dds::DataReaderQos& qos) {
  return {ns_or_none(qos.liveliness().lease_duration), ns_or_none(qos.deadline().period)};
}

dds::DataWriterQos without_dds_timers(dds::DataWriterQos qos) { return without_timers(std::move(qos)); }
dds::DataReaderQos without_dds_timers(dds::DataReaderQos qos) { return without_timers(std::move(qos)); }

void apply_overrides(dds::DomainParticipantQos& qos, const ParticipantConfig& config) {
  if (!config.participant_lease_ns) return;
  auto& discovery = qos.wire_protocol().builtin.discovery_config;
  discovery.leaseDuration = to_dds_duration(*config.participant_lease_ns);
  discovery.leaseDuration_announcementperiod = to_dds_duration(*config.participant_lease_ns / 3);
}

}  // namespace teleop::transport
