// The `ros2:` keys of a follower's section: defaults as ros2_control's examples name things, and
// a clear error for what cannot work.
#include <gtest/gtest.h>

#include "follower_section.h"
#include "teleop/robot/ros2_backend.h"

namespace teleop::robot {
namespace {

Ros2HardwareConfig parse(const std::string& yaml) { return test::parse_follower_section(yaml, parse_ros2_hardware); }
std::string error_of(const std::string& yaml) { return test::follower_section_error(yaml, parse_ros2_hardware); }

TEST(Ros2HardwareConfig, DefaultsFollowRos2ControlsExamples) {
  const Ros2HardwareConfig c = parse("follower:\n  ros2:\n    joints: [j1, j2]\n");
  EXPECT_EQ(c.joints, (std::vector<std::string>{"j1", "j2"}));
  EXPECT_EQ(c.interface, Ros2CommandInterface::kEffort);
  EXPECT_EQ(c.command_topic, "/forward_effort_controller/commands");
  EXPECT_EQ(c.state_topic, "/joint_states");
  EXPECT_EQ(c.participant.domain_id, 0);
  EXPECT_DOUBLE_EQ(c.state_timeout_s, 0.02);
  EXPECT_TRUE(c.phase_lock);
  EXPECT_DOUBLE_EQ(c.phase_lock_lead_s, 150e-6);
  const Ros2HardwareConfig p = parse("follower:\n  ros2:\n    joints: [j1]\n    interface: position\n"
                                     "    transport: {domain_id: 7, initial_peers: [127.0.0.1]}\n");
  EXPECT_EQ(p.command_topic, "/forward_position_controller/commands");
  EXPECT_EQ(p.participant.domain_id, 7);
  EXPECT_EQ(p.participant.initial_peers, (std::vector<std::string>{"127.0.0.1"}));
}

TEST(Ros2HardwareConfig, RefusesWhatCannotWork) {
  EXPECT_NE(error_of("follower:\n  ros2: {interface: effort}\n").find("ros2.joints: is required"), std::string::npos);
  EXPECT_NE(error_of("follower:\n  ros2: {joints: [a, b, a]}\n").find("names a twice"), std::string::npos);
  EXPECT_NE(error_of("follower:\n  ros2: {joints: [a], ignored_joints: [a]}\n").find("ros2.ignored_joints: names a twice"),
            std::string::npos);
  EXPECT_NE(error_of("follower:\n  ros2: {joints: [a], gravity_compensated: false}\n").find("zero effort"), std::string::npos);
  EXPECT_NE(error_of("follower:\n  ros2: {joints: [a], state_topic: joint_states}\n").find("starts with '/'"),
            std::string::npos);
  EXPECT_NE(error_of("follower:\n  ros2: {joints: [a, b], max_torque_nm: [10]}\n").find("1 values for 2 joints"),
            std::string::npos);
  EXPECT_NE(error_of("follower:\n  ros2: {joints: [a], interface: torque}\n").find("ros2.interface"), std::string::npos);
  // a lead of a whole cycle or more would put the follower's cycle after the robot's next one
  EXPECT_NE(error_of("follower:\n  ros2: {joints: [a], phase_lock_lead_us: 1000}\n").find("ros2.phase_lock_lead_us"),
            std::string::npos);
}

}  // namespace
}  // namespace teleop::robot
