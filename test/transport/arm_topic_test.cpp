#include "teleop/transport/arm_topic.h"

#include <gtest/gtest.h>

#include <string>

namespace teleop::transport {
namespace {

std::string name_of(const TopicSpec<msg::JointState>& spec) { return spec.name; }

TEST(ArmTopic, AppendsTheArmsNameAndKeepsTheQos) {
  const auto left = arm_topic(topics::kFollowerState, "left");
  EXPECT_EQ(left.name(), "teleop/follower/joint_state/left");
  EXPECT_EQ(name_of(left), "teleop/follower/joint_state/left") << "the spec a Publication sees";
  EXPECT_EQ(static_cast<const TopicSpec<msg::JointState>&>(left).qos, topics::kFollowerState.qos);
}

TEST(ArmTopic, KeepsThePlainNameForTheUnnamedArmOfAOneArmRobot) {
  EXPECT_EQ(name_of(arm_topic(topics::kFollowerState, "")), "teleop/follower/joint_state");
  EXPECT_STREQ(arm_label(""), "single");
  EXPECT_STREQ(arm_label(std::string("right")), "right");
}

}  // namespace
}  // namespace teleop::transport
