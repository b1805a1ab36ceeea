#include "teleop/transport/qos.h"

#include <gtest/gtest.h>

#include <string>

namespace teleop::transport {
namespace {

namespace dds = eprosima::fastdds::dds;

ParticipantConfig config() {
  ParticipantConfig c;
  c.liveliness_lease_ns = 1'250'000'000;  // 1.25 s: seconds and nanoseconds both non-zero
  c.stream_deadline_ns = 3'500'000;
  return c;
}

int64_t ns_of(const eprosima::fastrtps::Duration_t& d) {
  return static_cast<int64_t>(d.seconds) * 1'000'000'000 + static_cast<int64_t>(d.nanosec);
}

TEST(Qos, NamesEachPreset) {
  EXPECT_EQ(std::string(to_string(QosPreset::kStream)), "stream");
  EXPECT_EQ(std::string(to_string(QosPreset::kState)), "state");
}

TEST(Qos, ConvertsNanosecondsToDdsDurationExactly) {
  const auto d = to_dds_duration(3'000'000'007);
  EXPECT_EQ(d.seconds, 3);
  EXPECT_EQ(d.nanosec, 7u);
  EXPECT_EQ(ns_of(to_dds_duration(999'999'999)), 999'999'999);
  EXPECT_EQ(ns_of(to_dds_duration(0)), 0);
}

TEST(Qos, StreamWriterIsBestEffortVolatileKeepLastOneWithDeadline) {
  const dds::DataWriterQos q = writer_qos(QosPreset::kStream, config());
  EXPECT_EQ(q.reliability().kind, dds::BEST_EFFORT_RELIABILITY_QOS);
  EXPECT_EQ(q.durability().kind, dds::VOLATILE_DURABILITY_QOS);
  EXPECT_EQ(q.history().kind, dds::KEEP_LAST_HISTORY_QOS);
  EXPECT_EQ(q.history().depth, 1);
  EXPECT_EQ(ns_of(q.deadline().period), 3'500'000);
  EXPECT_EQ(q.publish_mode().kind, dds::SYNCHRONOUS_PUBLISH_MODE);
}

TEST(Qos, StreamReaderKeepsStreamDepthAndPreallocatesExactlyIt) {
  const dds::DataReaderQos q = reader_qos(QosPreset::kStream, config());
  EXPECT_EQ(q.reliability().kind, dds::BEST_EFFORT_RELIABILITY_QOS);
  EXPECT_EQ(q.durability().kind, dds::VOLATILE_DURABILITY_QOS);
  EXPECT_EQ(q.history().kind, dds::KEEP_LAST_HISTORY_QOS);
  EXPECT_EQ(q.history().depth, kReaderDepth);
  EXPECT_EQ(ns_of(q.deadline().period), 3'500'000);
  EXPECT_EQ(q.resource_limits().max_instances, 1);
  EXPECT_EQ(q.resource_limits().max_samples_per_instance, kReaderDepth);
  EXPECT_EQ(q.resource_limits().max_samples, kReaderDepth);
  EXPECT_EQ(q.resource_limits().allocated_samples, kReaderDepth);
}

TEST(Qos, StateWriterIsReliableTransientLocalKeepLastOne) {
  const dds::DataWriterQos q = writer_qos(QosPreset::kState, config());
  EXPECT_EQ(q.reliability().kind, dds::RELIABLE_RELIABILITY_QOS);
  EXPECT_EQ(q.durability().kind, dds::TRANSIENT_LOCAL_DURABILITY_QOS);
  EXPECT_EQ(q.history().kind, dds::KEEP_LAST_HISTORY_QOS);
  EXPECT_EQ(q.history().depth, 1);
  // a state topic has no deadline: it is published at a low rate
  EXPECT_EQ(q.deadline().period, eprosima::fastrtps::c_TimeInfinite);
  // a lost state sample is repaired quickly, and a full history never blocks the loop for long
  EXPECT_EQ(ns_of(q.reliable_writer_qos().times.heartbeatPeriod), 100'000'000);
  EXPECT_LE(ns_of(q.reliability().max_blocking_time), 1'000'000);
}

TEST(Qos, StateReaderIsReliableTransientLocalAndKeepsWhatArrivesBetweenPolls) {
  const dds::DataReaderQos q = reader_qos(QosPreset::kState, config());
  EXPECT_EQ(q.reliability().kind, dds::RELIABLE_RELIABILITY_QOS);
  EXPECT_EQ(q.durability().kind, dds::TRANSIENT_LOCAL_DURABILITY_QOS);
  EXPECT_EQ(q.history().kind, dds::KEEP_LAST_HISTORY_QOS);
  EXPECT_EQ(q.history().depth, kReaderDepth);
  EXPECT_EQ(q.deadline().period, eprosima::fastrtps::c_TimeInfinite);
  EXPECT_EQ(q.resource_limits().max_samples, kReaderDepth);
  EXPECT_EQ(q.resource_limits().max_samples_per_instance, kReaderDepth);
}

TEST(Qos, EveryPresetCarriesLivelinessWithConfiguredLease) {
  for (QosPreset preset : {QosPreset::kStream, QosPreset::kState}) {
    const dds::DataWriterQos w = writer_qos(preset, config());
    const dds::DataReaderQos r = reader_qos(preset, config());
    // streams: asserted per writer by its writes (see qos.cpp: Fast DDS 2.9 automatic liveliness
    // is not tracked per participant); states: automatic
    const auto kind =
        preset == QosPreset::kStream ? dds::MANUAL_BY_TOPIC_LIVELINESS_QOS : dds::AUTOMATIC_LIVELINESS_QOS;
    EXPECT_EQ(w.liveliness().kind, kind) << to_string(preset);
    EXPECT_EQ(r.liveliness().kind, kind) << to_string(preset);
    EXPECT_EQ(ns_of(w.liveliness().lease_duration), 1'250'000'000) << to_string(preset);
    EXPECT_EQ(ns_of(r.liveliness().lease_duration), 1'250'000'000) << to_string(preset);
    // the writer asserts three times per lease
    EXPECT_EQ(ns_of(w.liveliness().announcement_period), 1'250'000'000 / 3) << to_string(preset);
    EXPECT_LT(ns_of(w.liveliness().announcement_period), ns_of(w.liveliness().lease_duration));
  }
}

TEST(Qos, EveryPresetHasDataSharingOff) {
  for (QosPreset preset : {QosPreset::kStream, QosPreset::kState}) {
    EXPECT_EQ(writer_qos(preset, config()).data_sharing().kind(), dds::DataSharingKind::OFF) << to_string(preset);
    EXPECT_EQ(reader_qos(preset, config()).data_sharing().kind(), dds::DataSharingKind::OFF) << to_string(preset);
  }
}

TEST(Qos, EveryPresetPreallocatesPayloads) {
  for (QosPreset preset : {QosPreset::kStream, QosPreset::kState}) {
    EXPECT_EQ(writer_qos(preset, config()).endpoint().history_memory_policy,
              eprosima::fastrtps::rtps::PREALLOCATED_WITH_REALLOC_MEMORY_MODE);
    EXPECT_EQ(reader_qos(preset, config()).endpoint().history_memory_policy,
              eprosima::fastrtps::rtps::PREALLOCATED_WITH_REALLOC_MEMORY_MODE);
  }
}

TEST(Qos, WriterAndReaderOfEachPresetAreCompatible) {
  // a reader matches a writer only if it requests no more than the writer offers
  for (QosPreset preset : {QosPreset::kStream, QosPreset::kState}) {
    const dds::DataWriterQos w = writer_qos(preset, config());
    const dds::DataReaderQos r = reader_qos(preset, config());
    EXPECT_GE(w.reliability().kind, r.reliability().kind) << to_string(preset);
    EXPECT_GE(w.durability().kind, r.durability().kind) << to_string(preset);
    EXPECT_LE(ns_of(w.liveliness().lease_duration), ns_of(r.liveliness().lease_duration)) << to_string(preset);
    EXPECT_EQ(w.deadline().period, r.deadline().period) << to_string(preset);
  }
}

TEST(Qos, StreamEndpointsGoOnTheWireWithoutDdsTimersAndTheirReadersKeepTheChecks) {
  // what the stream preset names is checked by the reader (StreamFreshness); DDS gets neither
  const dds::DataReaderQos r = reader_qos(QosPreset::kStream, config());
  const StreamChecks checks = stream_checks(r);
  EXPECT_EQ(checks.lease_ns, 1'250'000'000);
  EXPECT_EQ(checks.deadline_ns, 3'500'000);
  const dds::DataReaderQos wire_r = without_dds_timers(r);
  const dds::DataWriterQos wire_w = without_dds_timers(writer_qos(QosPreset::kStream, config()));
  for (const auto* l : {&wire_r.liveliness(), &wire_w.liveliness()}) {
    EXPECT_EQ(l->kind, dds::AUTOMATIC_LIVELINESS_QOS);
    EXPECT_EQ(l->lease_duration, eprosima::fastrtps::c_TimeInfinite);
    EXPECT_EQ(l->announcement_period, eprosima::fastrtps::c_TimeInfinite);
  }
  EXPECT_EQ(wire_r.deadline().period, eprosima::fastrtps::c_TimeInfinite);
  EXPECT_EQ(wire_w.deadline().period, eprosima::fastrtps::c_TimeInfinite);
  // everything else as the preset says
  EXPECT_EQ(wire_r.reliability().kind, r.reliability().kind);
  EXPECT_EQ(wire_r.history().depth, r.history().depth);
  // none named: none checked
  EXPECT_EQ(stream_checks(wire_r).lease_ns, 0);
  EXPECT_EQ(stream_checks(wire_r).deadline_ns, 0);
}

}  // namespace
}  // namespace teleop::transport

namespace teleop::transport {
namespace {

TEST(Qos, EventPresetIsReliableKeepAllWithFastHeartbeats) {
  ParticipantConfig c;
  const auto w = writer_qos(QosPreset::kEvent, c);
  const auto r = reader_qos(QosPreset::kEvent, c);
  EXPECT_EQ(w.reliability().kind, eprosima::fastdds::dds::RELIABLE_RELIABILITY_QOS);
  EXPECT_EQ(w.history().kind, eprosima::fastdds::dds::KEEP_ALL_HISTORY_QOS);
  EXPECT_EQ(r.history().kind, eprosima::fastdds::dds::KEEP_ALL_HISTORY_QOS);
  EXPECT_EQ(w.durability().kind, eprosima::fastdds::dds::VOLATILE_DURABILITY_QOS);
  EXPECT_EQ(w.resource_limits().max_samples, kEventQueueDepth);
  EXPECT_EQ(r.resource_limits().max_samples, kEventQueueDepth);
  EXPECT_EQ(w.reliable_writer_qos().times.heartbeatPeriod, to_dds_duration(20'000'000));
  EXPECT_STREQ(to_string(QosPreset::kEvent), "event");
}

}  // namespace
}  // namespace teleop::transport
