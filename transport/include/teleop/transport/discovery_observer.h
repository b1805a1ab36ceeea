#pragma once
// What a participant learns from discovery about the others on the domain: their names and hosts,
// and every reader and writer with its topic, type and QoS. Tools (`teleop topic`, `teleop
// record`) watch the bus through this; nodes do not need it.

#include <array>
#include <cstdint>
#include <string>

#include "teleop/common/stream_session.h"

namespace teleop::transport {

/// The GUID prefix of a participant: the first 12 bytes of each of its endpoints' GUIDs.
using ParticipantId = std::array<uint8_t, 12>;

struct ParticipantInfo {
  ParticipantId id{};
  /// The participant's name (a node's name).
  std::string name;
  /// The host it runs on, as it announced it (the `teleop.host` property; its first unicast
  /// address for participants that do not announce one).
  std::string host;
};

struct EndpointInfo {
  /// The DataWriter's or DataReader's GUID.
  WriterId guid;
  bool is_writer = false;
  std::string topic;
  /// The DDS type name, e.g. "teleop::msg::JointState".
  std::string type;
  bool reliable = false;
  bool transient_local = false;
  /// The offered (writer) or requested (reader) deadline; 0: none.
  int64_t deadline_ns = 0;
  /// The liveliness lease; 0: infinite.
  int64_t lease_ns = 0;

  ParticipantId participant() const {
    ParticipantId p{};
    for (size_t i = 0; i < p.size(); ++i) p[i] = guid.bytes[i];
    return p;
  }
};

/// Called on Fast DDS threads; implementations synchronise themselves.
class DiscoveryObserver {
 public:
  virtual ~DiscoveryObserver() = default;
  /// A participant appeared (`present`) or left (removed, dropped after its lease).
  virtual void on_participant(const ParticipantInfo& participant, bool present) = 0;
  /// An endpoint appeared or changed its QoS (`present`), or went away.
  virtual void on_endpoint(const EndpointInfo& endpoint, bool present) = 0;
};

}  // namespace teleop::transport
