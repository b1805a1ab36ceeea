#include "impairment/rtps_classifier.h"

#include <gtest/gtest.h>

#include <vector>

namespace teleop::transport::impairment {
namespace {

// an RTPS message with one submessage of `id` whose reader/writer entity ids are given
std::vector<uint8_t> message(uint8_t id, uint32_t reader, uint32_t writer, bool little_endian = true) {
  std::vector<uint8_t> m = {'R', 'T', 'P', 'S', 2, 3, 1, 15};
  m.resize(20, 0xab);  // GUID prefix
  const bool data = id == 0x15 || id == 0x16;
  const uint16_t length = static_cast<uint16_t>((data ? 4 : 0) + 8 + 8);
  m.push_back(id);
  m.push_back(little_endian ? 0x01 : 0x00);
  m.push_back(static_cast<uint8_t>(little_endian ? length & 0xff : length >> 8));
  m.push_back(static_cast<uint8_t>(little_endian ? length >> 8 : length & 0xff));
  if (data) m.insert(m.end(), {0, 0, 16, 0});  // extraFlags, octetsToInlineQos
  for (uint32_t e : {reader, writer}) {
    // entity ids are byte arrays: key (3 bytes) then kind
    m.push_back(static_cast<uint8_t>(e >> 24));
    m.push_back(static_cast<uint8_t>(e >> 16));
    m.push_back(static_cast<uint8_t>(e >> 8));
    m.push_back(static_cast<uint8_t>(e));
  }
  m.resize(m.size() + 8, 0);  // the rest of the body
  return m;
}

constexpr uint32_t kSpdpWriter = 0x000100c2;
constexpr uint32_t kSedpPublicationsWriter = 0x000003c2;
constexpr uint32_t kSedpSubscriptionsReader = 0x000004c7;
constexpr uint32_t kWlpWriter = 0x000200c2;
constexpr uint32_t kUserWriter = 0x00000102;
constexpr uint32_t kUserReader = 0x00000107;

TEST(RtpsClassifier, RecognisesParticipantAndEndpointDiscovery) {
  auto spdp = message(0x15, 0, kSpdpWriter);
  EXPECT_TRUE(is_discovery_message(spdp.data(), static_cast<uint32_t>(spdp.size())));
  auto sedp = message(0x07, 0, kSedpPublicationsWriter, /*little_endian=*/false);
  EXPECT_TRUE(is_discovery_message(sedp.data(), static_cast<uint32_t>(sedp.size())));
  auto acknack = message(0x06, kSedpSubscriptionsReader, 0);
  EXPECT_TRUE(is_discovery_message(acknack.data(), static_cast<uint32_t>(acknack.size())));
}

TEST(RtpsClassifier, TreatsUserDataAndLivelinessAsNotDiscovery) {
  auto user = message(0x15, kUserReader, kUserWriter);
  EXPECT_FALSE(is_discovery_message(user.data(), static_cast<uint32_t>(user.size())));
  auto heartbeat = message(0x07, kUserReader, kUserWriter);
  EXPECT_FALSE(is_discovery_message(heartbeat.data(), static_cast<uint32_t>(heartbeat.size())));
  auto wlp = message(0x15, 0, kWlpWriter);
  EXPECT_FALSE(is_discovery_message(wlp.data(), static_cast<uint32_t>(wlp.size())))
      << "liveliness must stay impaired, or outages could not expire leases";
}

TEST(RtpsClassifier, RejectsMalformedMessagesWithoutReadingPastTheEnd) {
  const uint8_t not_rtps[24] = {'X', 'T', 'P', 'S'};
  EXPECT_FALSE(is_discovery_message(not_rtps, sizeof(not_rtps)));
  auto truncated = message(0x15, 0, kSpdpWriter);
  truncated.resize(26);  // the entity ids are cut off
  EXPECT_FALSE(is_discovery_message(truncated.data(), static_cast<uint32_t>(truncated.size())));
  EXPECT_FALSE(is_discovery_message(nullptr, 0));
}

}  // namespace
}  // namespace teleop::transport::impairment
