#include "foxglove_protocol.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <stdexcept>

namespace teleop::bridge {
namespace {

using nlohmann::json;

constexpr uint8_t kMessageDataOpcode = 0x01;

template <typename T>
void put_little_endian(std::string& out, T value) {
  for (size_t i = 0; i < sizeof(T); ++i) out.push_back(static_cast<char>((value >> (8 * i)) & 0xff));
}

// an id of the protocol: a uint32, not any number JSON can carry
uint32_t id_of(const json& value) {
  if (!value.is_number_unsigned() || value.get<uint64_t>() > UINT32_MAX) {
    throw std::invalid_argument("an id must be an unsigned 32-bit number, not " + value.dump());
  }
  return value.get<uint32_t>();
}

ClientRequest subscribe_request(const json& message) {
  ClientRequest request{ClientRequest::Op::kSubscribe, {}, {}, {}};
  for (const json& s : message.at("subscriptions")) {
    request.subscriptions.emplace_back(id_of(s.at("id")), id_of(s.at("channelId")));
  }
  return request;
}

ClientRequest unsubscribe_request(const json& message) {
  ClientRequest request{ClientRequest::Op::kUnsubscribe, {}, {}, {}};
  for (const json& id : message.at("subscriptionIds")) request.unsubscriptions.push_back(id_of(id));
  return request;
}

}  // namespace

std::string server_info_json(const std::string& name, const std::string& session_id) {
  // no capabilities: no client publishing, parameters or services (a read-only view of the bus)
  return json{{"op", "serverInfo"},
              {"name", name},
              {"capabilities", json::array()},
              {"supportedEncodings", json::array()},
              {"metadata", json::object()},
              {"sessionId", session_id}}
      .dump();
}

std::string advertise_json(const std::vector<Channel>& channels) {
  json list = json::array();
  for (const Channel& c : channels) {
    list.push_back({{"id", c.id},
                    {"topic", c.topic},
                    {"encoding", c.encoding},
                    {"schemaName", c.schema_name},
                    {"schema", c.schema},
                    {"schemaEncoding", c.schema_encoding}});
  }
  return json{{"op", "advertise"}, {"channels", list}}.dump();
}

std::string status_json(StatusLevel level, const std::string& message) {
  return json{{"op", "status"}, {"level", static_cast<int>(level)}, {"message", message}}.dump();
}

std::string message_data_frame(uint32_t subscription_id, uint64_t receive_ns, const uint8_t* payload, size_t size) {
  std::string frame;
  frame.reserve(1 + 4 + 8 + size);
  frame.push_back(static_cast<char>(kMessageDataOpcode));
  put_little_endian(frame, subscription_id);
  put_little_endian(frame, receive_ns);
  frame.append(reinterpret_cast<const char*>(payload), size);
  return frame;
}

ClientRequest parse_client_request(std::string_view text) {
  try {
    const json message = json::parse(text);
    const std::string op = message.at("op").get<std::string>();
    if (op == "subscribe") return subscribe_request(message);
    if (op == "unsubscribe") return unsubscribe_request(message);
    return {ClientRequest::Op::kUnsupported, {}, {}, op};
  } catch (const std::exception& e) {  // bad JSON, a missing field, a wrong type, an id out of range
    return {ClientRequest::Op::kMalformed, {}, {}, e.what()};
  }
}

}  // namespace teleop::bridge
