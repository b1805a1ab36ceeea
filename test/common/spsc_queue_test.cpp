#include "teleop/common/spsc_queue.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <thread>

namespace teleop {
namespace {

TEST(SpscQueue, KeepsOrderAndDropsWhatDoesNotFitCountingIt) {
  SpscQueue<int, 4> q;
  for (int i = 0; i < 6; ++i) (void)q.push(i);
  EXPECT_EQ(q.dropped(), 2u);
  int v = -1;
  for (int i = 0; i < 4; ++i) {
    ASSERT_TRUE(q.pop(v));
    EXPECT_EQ(v, i);
  }
  EXPECT_FALSE(q.pop(v));
  EXPECT_TRUE(q.push(7)) << "room again once consumed";
  ASSERT_TRUE(q.pop(v));
  EXPECT_EQ(v, 7);
}

TEST(SpscQueue, EveryRecordArrivesOnceInOrderAcrossThreadsAndEveryRefusalIsCounted) {
  SpscQueue<uint64_t, 64> q;
  constexpr uint64_t kRecords = 200'000;
  uint64_t received = 0;
  bool in_order = true;
  std::thread consumer([&] {
    uint64_t v = 0, last = 0;
    while (last < kRecords) {
      if (!q.pop(v)) continue;
      in_order = in_order && v == last + 1;
      last = v;
      ++received;
    }
  });
  uint64_t refused = 0;
  for (uint64_t i = 1; i <= kRecords; ++i) {
    // a producer that must not lose anything retries; the queue counts each refusal
    while (!q.push(i)) ++refused;
  }
  consumer.join();
  EXPECT_TRUE(in_order);
  EXPECT_EQ(received, kRecords);
  EXPECT_EQ(q.dropped(), refused);
}

}  // namespace
}  // namespace teleop
