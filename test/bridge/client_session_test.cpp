#include "client_session.h"

#include <gtest/gtest.h>

namespace teleop::bridge {
namespace {

constexpr int64_t kMs = 1'000'000;

// offers a CDR payload of five bytes
bool offer(ClientSession& client, uint32_t channel, int64_t now_ns) {
  static const uint8_t payload[] = {0x00, 0x01, 0x00, 0x00, 0x2a};
  return client.offer(channel, payload, sizeof payload, 77, now_ns);
}

uint32_t subscription_of(const std::string& frame) {
  uint32_t id = 0;
  for (int i = 0; i < 4; ++i) id |= static_cast<uint32_t>(static_cast<uint8_t>(frame[1 + i])) << (8 * i);
  return id;
}

TEST(BridgeClientSession, OnlySubscribedChannelsAreQueuedWithTheirSubscriptionId) {
  ClientSession client("peer", 0.0, 16);
  EXPECT_FALSE(offer(client, 1, 0));
  EXPECT_EQ(client.queue().size(), 0u);
  ASSERT_EQ(client.subscribe(9, 1), std::nullopt);
  EXPECT_TRUE(offer(client, 1, 0));  // the first frame wakes the sender
  EXPECT_FALSE(offer(client, 1, 1));
  EXPECT_FALSE(offer(client, 2, 2));  // another channel
  ASSERT_EQ(client.queue().size(), 2u);
  const std::string frame = *client.queue().pop();
  EXPECT_EQ(subscription_of(frame), 9u);
  EXPECT_EQ(frame.size(), 1u + 4 + 8 + 5);
}

TEST(BridgeClientSession, RefusesATakenIdOrAChannelTwice) {
  ClientSession client("peer", 0.0, 16);
  ASSERT_EQ(client.subscribe(1, 10), std::nullopt);
  EXPECT_NE(client.subscribe(1, 11), std::nullopt);
  EXPECT_NE(client.subscribe(2, 10), std::nullopt);
  EXPECT_NE(client.unsubscribe(5), std::nullopt);
  EXPECT_EQ(client.unsubscribe(1), std::nullopt);
  EXPECT_FALSE(offer(client, 10, 0));
  EXPECT_EQ(client.subscribe(1, 11), std::nullopt);  // the id is free again
}

TEST(BridgeClientSession, CountsWhatTheRateLimitHoldsBackAndTheQueueDrops) {
  ClientSession client("peer", 50.0, 4);
  ASSERT_EQ(client.subscribe(0, 1), std::nullopt);
  // one second at 1 kHz: 50 pass the limit, 950 are held back; 46 of the 50 fall out of the queue
  for (int i = 0; i < 1000; ++i) offer(client, 1, i * kMs);
  const ClientStats s = client.stats();
  EXPECT_EQ(s.limited + s.dropped + client.queue().size(), 1000u);
  EXPECT_GE(s.limited, 949u);
  EXPECT_EQ(client.queue().size(), 4u);
  EXPECT_EQ(s.sent, 0u);
  client.count_sent();
  EXPECT_EQ(client.stats().sent, 1u);
}

}  // namespace
}  // namespace teleop::bridge
