#include "send_queue.h"

#include <gtest/gtest.h>

#include <atomic>
#include <thread>

namespace teleop::bridge {
namespace {

TEST(BridgeSendQueue, KeepsOrderUnderItsCapacity) {
  SendQueue queue(3);
  EXPECT_TRUE(queue.push("a"));  // was empty: wake the sender
  EXPECT_FALSE(queue.push("b"));
  EXPECT_EQ(queue.size(), 2u);
  EXPECT_EQ(queue.pop(), "a");
  EXPECT_EQ(queue.pop(), "b");
  EXPECT_EQ(queue.pop(), std::nullopt);
  EXPECT_EQ(queue.dropped(), 0u);
}

TEST(BridgeSendQueue, WhenFullTheOldestMakesRoomAndIsCounted) {
  SendQueue queue(3);
  for (const char* f : {"1", "2", "3", "4", "5"}) queue.push(f);
  EXPECT_EQ(queue.size(), 3u);
  EXPECT_EQ(queue.dropped(), 2u);
  EXPECT_EQ(queue.pop(), "3");  // the newest three stay
  EXPECT_EQ(queue.pop(), "4");
  EXPECT_EQ(queue.pop(), "5");
}

TEST(BridgeSendQueue, ZeroCapacityStillHoldsTheNewest) {
  SendQueue queue(0);
  queue.push("old");
  queue.push("new");
  EXPECT_EQ(queue.pop(), "new");
  EXPECT_EQ(queue.dropped(), 1u);
}

TEST(BridgeSendQueue, EveryFrameIsSentDroppedOrStillWaitingAcrossThreads) {
  SendQueue queue(64);
  constexpr int kPerProducer = 20'000;
  std::atomic<bool> producing{true};
  uint64_t popped = 0;
  std::thread consumer([&] {
    while (producing.load() || queue.size() > 0) {
      if (queue.pop()) ++popped;
    }
  });
  std::thread a([&] {
    for (int i = 0; i < kPerProducer; ++i) queue.push("a");
  });
  std::thread b([&] {
    for (int i = 0; i < kPerProducer; ++i) queue.push("b");
  });
  a.join();
  b.join();
  producing.store(false);
  consumer.join();
  EXPECT_EQ(popped + queue.dropped() + queue.size(), 2u * kPerProducer);
  EXPECT_LE(queue.size(), 64u);
}

}  // namespace
}  // namespace teleop::bridge
