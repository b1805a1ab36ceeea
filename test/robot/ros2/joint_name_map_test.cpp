// A ROS 2 JointState's joints are matched by name: any order, ignored extras, and a clear error
// naming what is missing, repeated or unexpected.
#include <gtest/gtest.h>

#include "joint_name_map.h"

namespace teleop::robot {
namespace {

TEST(JointNameMap, MapsByNameInAnyOrder) {
  JointNameMap map({"a", "b", "c"}, {"finger"});
  ASSERT_TRUE(map.map({"c", "finger", "a", "b"}));
  EXPECT_EQ(map.index(0), 2u);
  EXPECT_EQ(map.index(1), 3u);
  EXPECT_EQ(map.index(2), 0u);
  ASSERT_TRUE(map.map({"a", "b", "c"}));
  EXPECT_EQ(map.index(0), 0u);
  EXPECT_EQ(map.index(2), 2u);
}

TEST(JointNameMap, RefusesMissingRepeatedAndUnexpectedJoints) {
  JointNameMap map({"a", "b", "c"}, {"finger"});
  EXPECT_FALSE(map.map({"a", "b"}));
  EXPECT_FALSE(map.map({"a", "b", "c", "a"}));
  EXPECT_FALSE(map.map({"a", "b", "c", "wrist"}));
  EXPECT_EQ(map.mismatch({"a", "a", "wrist"}),
            "missing: b, c; named twice: a; not configured (ros2.joints or ros2.ignored_joints): wrist");
  EXPECT_EQ(map.mismatch({"c", "b", "a", "finger"}), "");
}

}  // namespace
}  // namespace teleop::robot
