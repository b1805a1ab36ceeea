// The follower's measurement of its tracked objects for the twin (follower.tracked_objects): the
// configuration, the sample's fields, and the feed over DDS from the box task's shared scene.
#include "object_pose_feed.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>

#include "allocation_counter.h"
#include "node_harness.h"
#include "follower_arms.h"
#include "teleop/transport/subscription.h"
#include "teleop/transport/topics.h"

namespace teleop::follower {
namespace {

const std::string kBoxTaskFile = std::string(TELEOP_SOURCE_DIR) + "/config/nodes/follower_box_task.yaml";

// the box task's follower config with `extra` follower keys in place of its tracked_object* keys
// (paths resolve next to the real file)
ConfigNode box_task_config(const std::string& extra) {
  std::ifstream in(kBoxTaskFile);
  std::string yaml;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("  tracked_object", 0) != 0) yaml += line + "\n";
  }
  const std::string anchor = "  hardware: mujoco";
  yaml.replace(yaml.find(anchor), anchor.size(), anchor + "\n" + extra);
  return ConfigNode::load_string(yaml, kBoxTaskFile);
}

TEST(ObjectPoseFeedConfig, ReadsTheBodiesAndTheRate) {
  const auto arms = parse_follower_arms(box_task_config("  tracked_objects: [box]\n  tracked_object_rate_hz: 250"));
  ASSERT_EQ(arms.size(), 2u);
  EXPECT_EQ(arms[0].tracked_objects.bodies, std::vector<std::string>{"box"});
  EXPECT_DOUBLE_EQ(arms[0].tracked_objects.rate_hz, 250.0);
  const auto none = parse_follower_arms(box_task_config(""));
  EXPECT_TRUE(none[0].tracked_objects.bodies.empty()) << "absent: nothing is tracked";
}

TEST(ObjectPoseFeedConfig, NamesTheKeyOfAnOutOfRangeRate) {
  try {
    parse_follower_arms(box_task_config("  tracked_objects: [box]\n  tracked_object_rate_hz: 0"));
    FAIL() << "a rate of 0 was accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("follower.tracked_object_rate_hz"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("follower_box_task.yaml"), std::string::npos) << e.what();
  }
}

TEST(ObjectPoseFeed, WritesPoseAndTwistIntoTheirFields) {
  sim::BodyState s;
  s.position_m = {0.1, 0.2, 0.3};
  s.orientation_wxyz = {0.0, 1.0, 0.0, 0.0};
  s.linear_mps = {1.0, 2.0, 3.0};
  s.angular_radps = {-1.0, -2.0, -3.0};
  msg::ObjectPose sample;
  write_object_pose(s, sample);
  EXPECT_EQ(sample.world_pose().position_m().z(), 0.3);
  EXPECT_EQ(sample.world_pose().orientation().w(), 0.0);
  EXPECT_EQ(sample.world_pose().orientation().x(), 1.0);
  EXPECT_EQ(sample.world_twist().linear_mps().y(), 2.0);
  EXPECT_EQ(sample.world_twist().angular_radps().x(), -1.0);
}

class ObjectPoseFeedNodeTest : public ::testing::Test {
 protected:
  test::NodeHarness harness{"follower"};
  std::unique_ptr<runtime::NodeLogic> node =
      follower_logic_parser()(box_task_config("  tracked_objects: [box]\n  tracked_object_rate_hz: 100"))(harness.context);
  transport::Subscription<msg::ObjectPose> box{
      harness.peer, transport::TopicSpec<msg::ObjectPose>{"teleop/follower/object_pose/box", transport::QosPreset::kStream}};

  // cycles the follower (no commands: each arm holds its start pose); returns the allocations
  uint64_t run(int cycles) {
    uint64_t allocations = 0;
    for (int i = 0; i < cycles; ++i) {
      const CycleTick tick = harness.tick();
      test::ScopedAllocationCounter counter;
      node->cycle(tick);
      allocations += counter.count();
    }
    return allocations;
  }
};

TEST_F(ObjectPoseFeedNodeTest, PublishesTheBoxInItsSocketEveryTenthCycle) {
  ASSERT_TRUE(test::eventually([&] { return box.reader().matched() > 0; }));
  run(200);
  runtime::NodeReport report;
  node->fill_report(report);
  const auto topic = std::find_if(report.published.begin(), report.published.end(),
                                  [](const auto& t) { return t.topic == "teleop/follower/object_pose/box"; });
  ASSERT_NE(topic, report.published.end());
  EXPECT_EQ(topic->sent, 20u) << "one sample per 10 cycles: 100 Hz of a 1 kHz loop";
  // the reader matched the writer, but the writer may not have matched the reader yet (discovery
  // is per side; slow under ThreadSanitizer): cycles go on until a pose arrives
  ASSERT_TRUE(test::eventually([&] {
    if (box.poll() > 0 || box.has_sample()) return true;
    run(10);
    return false;
  }));
  const msg::ObjectPose& p = box.latest();
  EXPECT_EQ(std::string(p.body()), "box");
  // the box's body sits at (0.35, 0, 0.80) in scene_box_shelf.xml, resting in its socket
  EXPECT_NEAR(p.world_pose().position_m().x(), 0.35, 0.005);
  EXPECT_NEAR(p.world_pose().position_m().y(), 0.0, 0.005);
  EXPECT_NEAR(p.world_pose().position_m().z(), 0.80, 0.005);
  EXPECT_NEAR(std::abs(p.world_pose().orientation().w()), 1.0, 1e-3);
  EXPECT_LT(std::abs(p.world_twist().linear_mps().z()), 0.05) << "at rest";
}

TEST_F(ObjectPoseFeedNodeTest, CyclesWithoutAllocating) {
  run(50);
  EXPECT_EQ(run(200), 0u);
}

TEST(ObjectPoseFeedNode, NamesABodyTheSceneLacks) {
  test::NodeHarness harness{"follower"};
  try {
    follower_logic_parser()(box_task_config("  tracked_objects: [crate]"))(harness.context);
    FAIL() << "an unknown body was accepted";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("crate"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace teleop::follower
