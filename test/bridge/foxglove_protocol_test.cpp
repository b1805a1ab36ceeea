#include "foxglove_protocol.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

namespace teleop::bridge {
namespace {

using nlohmann::json;

TEST(BridgeFoxgloveProtocol, ServerInfoAdvertisesNoCapabilities) {
  const json info = json::parse(server_info_json("teleop bridge", "42"));
  EXPECT_EQ(info["op"], "serverInfo");
  EXPECT_EQ(info["name"], "teleop bridge");
  EXPECT_EQ(info["sessionId"], "42");
  EXPECT_TRUE(info["capabilities"].empty());  // read-only: no clientPublish
}

TEST(BridgeFoxgloveProtocol, AdvertiseCarriesTheRos2Schema) {
  const json advertise = json::parse(advertise_json({{3, "teleop/follower/joint_state", "teleop_msgs/msg/JointState",
                                                      "float64[] q_rad\n"}}));
  EXPECT_EQ(advertise["op"], "advertise");
  ASSERT_EQ(advertise["channels"].size(), 1u);
  const json& c = advertise["channels"][0];
  EXPECT_EQ(c["id"], 3);
  EXPECT_EQ(c["topic"], "teleop/follower/joint_state");
  EXPECT_EQ(c["encoding"], "cdr");
  EXPECT_EQ(c["schemaName"], "teleop_msgs/msg/JointState");
  EXPECT_EQ(c["schemaEncoding"], "ros2msg");
  EXPECT_EQ(c["schema"], "float64[] q_rad\n");
}

TEST(BridgeFoxgloveProtocol, AComputedChannelIsAdvertisedAsJson) {
  Channel scene{0, "scene/transforms", "foxglove.FrameTransforms", "{}", "json", "jsonschema"};
  const json c = json::parse(advertise_json({scene}))["channels"][0];
  EXPECT_EQ(c["encoding"], "json");
  EXPECT_EQ(c["schemaEncoding"], "jsonschema");
  EXPECT_EQ(c["schemaName"], "foxglove.FrameTransforms");
}

TEST(BridgeFoxgloveProtocol, MessageDataIsOpcodeSubscriptionTimeThenPayloadLittleEndian) {
  const uint8_t payload[] = {0x00, 0x01, 0x00, 0x00, 0xab};
  const std::string frame = message_data_frame(0x01020304, 0x1122334455667788ull, payload, sizeof payload);
  const std::string expected("\x01"
                             "\x04\x03\x02\x01"
                             "\x88\x77\x66\x55\x44\x33\x22\x11"
                             "\x00\x01\x00\x00\xab",
                             1 + 4 + 8 + 5);
  EXPECT_EQ(frame, expected);
}

TEST(BridgeFoxgloveProtocol, ReadsSubscribeAndUnsubscribe) {
  const ClientRequest sub =
      parse_client_request(R"({"op":"subscribe","subscriptions":[{"id":0,"channelId":3},{"id":7,"channelId":5}]})");
  ASSERT_EQ(sub.op, ClientRequest::Op::kSubscribe);
  ASSERT_EQ(sub.subscriptions.size(), 2u);
  EXPECT_EQ(sub.subscriptions[1], std::make_pair(7u, 5u));
  const ClientRequest unsub = parse_client_request(R"({"op":"unsubscribe","subscriptionIds":[0,7]})");
  ASSERT_EQ(unsub.op, ClientRequest::Op::kUnsubscribe);
  EXPECT_EQ(unsub.unsubscriptions, (std::vector<uint32_t>{0, 7}));
}

TEST(BridgeFoxgloveProtocol, PublishingIsUnsupportedAndGarbageMalformed) {
  const ClientRequest publish = parse_client_request(R"({"op":"advertise","channels":[]})");
  EXPECT_EQ(publish.op, ClientRequest::Op::kUnsupported);
  EXPECT_EQ(publish.detail, "advertise");
  for (const char* bad : {"", "{", "[]", R"({"op":1})", R"({"op":"subscribe"})",
                          R"({"op":"subscribe","subscriptions":[{"id":-1,"channelId":1}]})",
                          R"({"op":"unsubscribe","subscriptionIds":["x"]})"}) {
    EXPECT_EQ(parse_client_request(bad).op, ClientRequest::Op::kMalformed) << bad;
  }
}

}  // namespace
}  // namespace teleop::bridge
