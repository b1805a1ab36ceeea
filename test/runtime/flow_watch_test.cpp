// A node says once that it waits for a writer, and again when one appears.
#include <gtest/gtest.h>

#include "flow_watch.h"

namespace teleop::runtime {
namespace {

constexpr int64_t kS = 1'000'000'000;

TEST(FlowWaitTracker, ReportsAFlowWithoutWriterOnceAfterTheGraceTime) {
  FlowWaitTracker tracker(2, 3 * kS, 0);
  std::vector<FlowEvent> events;
  tracker.update(1 * kS, {0, 1}, events);
  EXPECT_TRUE(events.empty());
  tracker.update(3 * kS, {0, 1}, events);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].kind, FlowEvent::Kind::kWaiting);
  EXPECT_EQ(events[0].flow, 0u);
  EXPECT_DOUBLE_EQ(events[0].without_writer_s, 3.0);
  events.clear();
  tracker.update(10 * kS, {0, 1}, events);
  EXPECT_TRUE(events.empty()) << "said once, not every check";
}

TEST(FlowWaitTracker, ReportsTheWriterThatAppearsAfterTheWait) {
  FlowWaitTracker tracker(1, 3 * kS, 0);
  std::vector<FlowEvent> events;
  tracker.update(4 * kS, {0}, events);
  events.clear();
  tracker.update(6 * kS, {1}, events);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].kind, FlowEvent::Kind::kAppeared);
  EXPECT_DOUBLE_EQ(events[0].without_writer_s, 6.0);
}

TEST(FlowWaitTracker, AWriterWithinTheGraceTimeIsNotWorthAWord) {
  FlowWaitTracker tracker(1, 3 * kS, 0);
  std::vector<FlowEvent> events;
  tracker.update(1 * kS, {0}, events);
  tracker.update(2 * kS, {1}, events);
  EXPECT_TRUE(events.empty());
}

TEST(FlowWaitTracker, AWriterThatGoesAwayIsWaitedForAgain) {
  FlowWaitTracker tracker(1, 3 * kS, 0);
  std::vector<FlowEvent> events;
  tracker.update(1 * kS, {1}, events);
  tracker.update(5 * kS, {0}, events);  // gone since 5 s
  tracker.update(7 * kS, {0}, events);
  EXPECT_TRUE(events.empty());
  tracker.update(8 * kS, {0}, events);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].kind, FlowEvent::Kind::kWaiting);
  EXPECT_DOUBLE_EQ(events[0].without_writer_s, 3.0);
}

}  // namespace
}  // namespace teleop::runtime
