#include "teleop/common/refusal_memory.h"

#include <gtest/gtest.h>

namespace teleop {
namespace {

constexpr int64_t kS = 1'000'000'000;

WriterId writer(uint8_t id) {
  WriterId w;
  w.bytes.fill(id);
  return w;
}

TEST(RefusalMemory, ReportsTheFirstRefusalOfEachKindPerWriterOnly) {
  RefusalMemory m;
  EXPECT_TRUE(m.first(writer(1), 1, 0));
  EXPECT_FALSE(m.first(writer(1), 1, 1));
  EXPECT_TRUE(m.first(writer(1), 2, 2)) << "another kind of the same writer";
  EXPECT_TRUE(m.first(writer(2), 1, 3)) << "the same kind of another writer";
  EXPECT_FALSE(m.first(writer(2), 1, 10 * kS)) << "remembered, however long ago";
}

TEST(RefusalMemory, ForgetsTheOldestWriterWhenFullAndReportsItAgain) {
  RefusalMemory m;
  int64_t t = 0;
  for (uint8_t w = 1; w <= RefusalMemory::kWriters; ++w) ASSERT_TRUE(m.first(writer(w), 1, t += kS));
  EXPECT_TRUE(m.first(writer(100), 1, t += kS)) << "a ninth writer replaces the first";
  EXPECT_TRUE(m.first(writer(1), 1, t += kS)) << "the first was forgotten";
  EXPECT_FALSE(m.first(writer(3), 1, t += kS)) << "the others are still remembered";
}

TEST(RefusalMemory, AStormOfWritersCannotFloodTheLog) {
  RefusalMemory m;
  int reported = 0;
  for (int w = 0; w < 200; ++w) reported += m.first(writer(static_cast<uint8_t>(w)), 1, 1000 + w) ? 1 : 0;
  EXPECT_EQ(reported, RefusalMemory::kReportsPerSecond);
  // the next second has room again; a writer the rate held back is reported then
  EXPECT_TRUE(m.first(writer(150), 1, 2 * kS));
}

}  // namespace
}  // namespace teleop
