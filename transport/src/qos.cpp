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
void apply_common(Qos& qos, QosPreset preset, const ParticipantConfig& config) {
  qos.history().kind = dds::KEEP_LAST_HISTORY_QOS;
  qos.history().depth = 1;
  qos.liveliness().kind = dds::AUTOMATIC_LIVELINESS_QOS;
  qos.liveliness().lease_duration = to_dds_duration(config.liveliness_lease_ns);
  qos.data_sharing().off();
  // payloads preallocated at their bounded maximum: no allocation per sample
  qos.endpoint().history_memory_policy = eprosima::fastrtps::rtps::PREALLOCATED_WITH_REALLOC_MEMORY_MODE;
  switch (preset) {
    case QosPreset::kStream:
      // streams are written every cycle: their readers check deadline and liveliness from the
      // arrivals (stream_freshness.h), so DDS has neither. Fast DDS 2.9 re-arms a timer per
      // sample for each (measured: half the round trip, docs/benchmarks.md); and its automatic
      // liveliness keeps every automatic writer alive while any participant asserts it
      // (eProsima/Fast-DDS#4373), so a cut host among three nodes was never noticed (test/netns)
      // spelled out, not c_TimeInfinite: that is a per-file constant, still zero when a static
      // initializer elsewhere creates a writer before this file's (participant_test's helper)
      qos.liveliness().lease_duration = Duration_t(Duration_t::INFINITE_SECONDS, Duration_t::INFINITE_NANOSECONDS);
      qos.reliability().kind = dds::BEST_EFFORT_RELIABILITY_QOS;
      qos.durability().kind = dds::VOLATILE_DURABILITY_QOS;
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
  apply_common(qos, preset, config);
  // assert liveliness three times per lease so one lost announcement is not a death (streams:
  // their readers check it, a stream writer announces nothing)
  if (preset != QosPreset::kStream) {
    qos.liveliness().announcement_period = to_dds_duration(config.liveliness_lease_ns / 3);
  }
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
  return qos;
}

dds::DataReaderQos reader_qos(QosPreset preset, const ParticipantConfig& config) {
  dds::DataReaderQos qos = dds::DATAREADER_QOS_DEFAULT;
  apply_common(qos, preset, config);
  // readers are drained periodically: with unsynchronised loops two stream samples can arrive
  // between two polls, and several nodes write the one (unkeyed) status topic; a depth of 1
  // would silently overwrite (and hide) samples. Writers keep 1: late joiners get the last.
  qos.history().depth = preset == QosPreset::kEvent ? kEventQueueDepth : kReaderDepth;
  // preallocate exactly the history, nothing grows at run time
  qos.resource_limits().max_instances = 1;
  qos.resource_limits().max_samples_per_instance = qos.history().depth;
  qos.resource_limits().max_samples = qos.history().depth;
  qos.resource_limits().allocated_samples = qos.history().depth;
  return qos;
}

}  // namespace teleop::transport
