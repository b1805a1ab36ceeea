#pragma once
// The messages of the Foxglove WebSocket protocol (subprotocol foxglove.websocket.v1) the bridge
// speaks: it sends serverInfo, advertise, status (JSON text) and message data (binary); it reads
// subscribe and unsubscribe. Read-only: no client publishing is advertised, so anything else a
// client sends is answered with a status warning.

#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace teleop::bridge {

inline constexpr const char* kSubprotocol = "foxglove.websocket.v1";

/// A channel as advertised: a teleop topic with its type's ROS 2 schema, messages as CDR; or a
/// channel the bridge computes (JSON messages of a Foxglove schema, e.g. foxglove.FrameTransforms).
struct Channel {
  uint32_t id = 0;
  std::string topic;
  std::string schema_name;  ///< "teleop_msgs/msg/JointState"
  std::string schema;       ///< the ros2msg text with its dependencies
  std::string encoding = "cdr";
  std::string schema_encoding = "ros2msg";
};

enum class StatusLevel { kInfo = 0, kWarning = 1, kError = 2 };

std::string server_info_json(const std::string& name, const std::string& session_id);
std::string advertise_json(const std::vector<Channel>& channels);
std::string status_json(StatusLevel level, const std::string& message);

/// Message Data: opcode 0x01, subscription id (uint32), receive time [ns] (uint64), the payload;
/// little-endian.
std::string message_data_frame(uint32_t subscription_id, uint64_t receive_ns, const uint8_t* payload, size_t size);

/// What a client asked for in one text message.
struct ClientRequest {
  enum class Op { kSubscribe, kUnsubscribe, kUnsupported, kMalformed } op = Op::kMalformed;
  /// subscribe: (subscription id, channel id) pairs.
  std::vector<std::pair<uint32_t, uint32_t>> subscriptions;
  /// unsubscribe: subscription ids.
  std::vector<uint32_t> unsubscriptions;
  /// unsupported: the op's name; malformed: what is wrong.
  std::string detail;
};

/// Never throws: bad JSON or fields are a kMalformed request.
ClientRequest parse_client_request(std::string_view text);

}  // namespace teleop::bridge
