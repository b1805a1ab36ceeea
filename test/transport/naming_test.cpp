#include "teleop/transport/naming.h"

#include <gtest/gtest.h>

#include "teleop/transport/sample_types.h"

namespace teleop::transport {
namespace {

TEST(Naming, PlainNamesAreTheTeleopNames) {
  EXPECT_EQ(dds_topic_name(Naming::kPlain, "teleop/follower/joint_state"), "teleop/follower/joint_state");
  EXPECT_EQ(dds_type_name(Naming::kPlain, "teleop::msg::JointState"), "teleop::msg::JointState");
  EXPECT_EQ(teleop_topic_name(Naming::kPlain, "rt/teleop/follower/joint_state"), "rt/teleop/follower/joint_state");
}

TEST(Naming, Ros2NamesFollowRos2DdsConventions) {
  EXPECT_EQ(dds_topic_name(Naming::kRos2, "teleop/follower/joint_state"), "rt/teleop/follower/joint_state");
  EXPECT_EQ(dds_type_name(Naming::kRos2, "teleop::msg::JointState"), "teleop_msgs::msg::dds_::JointState_");
  EXPECT_EQ(ros2_type_name("teleop::msg::NodeStatus"), "teleop_msgs::msg::dds_::NodeStatus_");
}

TEST(Naming, Ros2DiscoveryNamesMapBackToTeleopTopicsAndOthersAreNotTeleops) {
  EXPECT_EQ(teleop_topic_name(Naming::kRos2, "rt/teleop/follower/joint_state"), "teleop/follower/joint_state");
  // a ROS 2 service's request topic, and a plain-named teleop topic on the same domain
  EXPECT_EQ(teleop_topic_name(Naming::kRos2, "rq/teleop/resetRequest"), std::nullopt);
  EXPECT_EQ(teleop_topic_name(Naming::kRos2, "teleop/follower/joint_state"), std::nullopt);
}

TEST(Naming, EverySampleTypeIsFoundByItsRos2Name) {
  for (const SampleType& type : sample_types()) {
    EXPECT_EQ(type.ros2_name, ros2_type_name(type.dds_name));
    EXPECT_EQ(find_sample_type(type.ros2_name), &type) << type.ros2_name;
    EXPECT_EQ(find_sample_type(type.dds_name), &type) << type.dds_name;
  }
  EXPECT_EQ(find_sample_type("teleop_msgs::msg::dds_::NoSuchType_"), nullptr);
}

}  // namespace
}  // namespace teleop::transport
