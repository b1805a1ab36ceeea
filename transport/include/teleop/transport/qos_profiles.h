#pragma once
// The QoS the nodes run with comes from a Fast DDS XML profiles file: one participant profile and
// a writer and a reader profile per preset (qos.h), named below. The shipped file,
// config/qos/teleop_profiles.xml, is compiled into the library; a node reads a replacement named
// by `transport.qos_profiles` in its YAML, else the FASTRTPS_DEFAULT_PROFILES_FILE when that
// defines the teleop profiles (docs/transport.md). Profiles are resolved once, when the
// participant is created: nothing on the control loop's path reads them.

#include <fastdds/dds/publisher/qos/DataWriterQos.hpp>
#include <fastdds/dds/subscriber/qos/DataReaderQos.hpp>

#include <array>
#include <cstddef>
#include <string_view>

#include "teleop/transport/qos.h"

namespace teleop::transport {

inline constexpr const char* kParticipantProfile = "teleop_participant";
/// "teleop_stream_writer", "teleop_state_writer", "teleop_event_writer".
const char* writer_profile_name(QosPreset preset);
/// "teleop_stream_reader", "teleop_state_reader", "teleop_event_reader".
const char* reader_profile_name(QosPreset preset);

/// The environment variable Fast DDS (and teleop) read a default profiles file from.
inline constexpr const char* kProfilesFileEnv = "FASTRTPS_DEFAULT_PROFILES_FILE";

/// config/qos/teleop_profiles.xml as it was when the library was built.
std::string_view builtin_qos_profiles();

/// The endpoint QoS of one participant: its profiles with its node's YAML overrides applied.
struct EndpointQos {
  static constexpr size_t kPresets = 3;
  std::array<eprosima::fastdds::dds::DataWriterQos, kPresets> writers;
  std::array<eprosima::fastdds::dds::DataReaderQos, kPresets> readers;

  const eprosima::fastdds::dds::DataWriterQos& writer(QosPreset preset) const {
    return writers[static_cast<size_t>(preset)];
  }
  const eprosima::fastdds::dds::DataReaderQos& reader(QosPreset preset) const {
    return readers[static_cast<size_t>(preset)];
  }
};

}  // namespace teleop::transport
