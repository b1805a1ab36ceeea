// teleop's types (idl/) and the DDS types ROS 2 makes of the teleop_msgs package
// (idl/ros2/teleop_msgs: the IDL rosidl would generate, by idl/ros2/msg_to_dds_idl.py, compiled by
// fastddsgen) are wire-identical: every sample serializes to the same bytes both ways, the ROS 2
// type reads each field under its own name, and both have the same serialized bound.

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <string>
#include <vector>

#include "teleop/transport/naming.h"
#include "teleop/transport/sample_types.h"
#include "teleop/transport/type_support.h"
#include "teleop_msgs/CartesianCommand_PubSubTypes.h"
#include "teleop_msgs/EmergencyStop_PubSubTypes.h"
#include "teleop_msgs/GeomDistances_PubSubTypes.h"
#include "teleop_msgs/HandCommand_PubSubTypes.h"
#include "teleop_msgs/HandState_PubSubTypes.h"
#include "teleop_msgs/JointCommand_PubSubTypes.h"
#include "teleop_msgs/JointState_PubSubTypes.h"
#include "teleop_msgs/JointTorque_PubSubTypes.h"
#include "teleop_msgs/NodeStatus_PubSubTypes.h"
#include "teleop_msgs/ObjectPose_PubSubTypes.h"
#include "teleop_msgs/ResetRequest_PubSubTypes.h"
#include "teleop_msgs/TdpaEnergy_PubSubTypes.h"
#include "teleop_msgs/WrenchStamped_PubSubTypes.h"

namespace teleop::transport {
namespace {

namespace ros = teleop_msgs::msg::dds_;
using Bytes = std::vector<uint8_t>;
using eprosima::fastrtps::rtps::SerializedPayload_t;

Bytes serialize(eprosima::fastdds::dds::TopicDataType& type, void* sample) {
  SerializedPayload_t payload(type.m_typeSize);
  EXPECT_TRUE(type.serialize(sample, &payload)) << type.getName();
  return Bytes(payload.data, payload.data + payload.length);
}

void deserialize(eprosima::fastdds::dds::TopicDataType& type, const Bytes& bytes, void* sample) {
  SerializedPayload_t payload(static_cast<uint32_t>(bytes.size()));
  std::memcpy(payload.data, bytes.data(), bytes.size());
  payload.length = static_cast<uint32_t>(bytes.size());
  ASSERT_TRUE(type.deserialize(&payload, sample)) << type.getName();
}

// ours -> bytes -> the ROS 2 type (checked by name) -> bytes again -> ours: nothing changes
template <typename Ours, typename RosPubSub, typename Ros>
void expect_wire_identical(const Ours& sample, const std::function<void(const Ros&)>& check_by_name) {
  typename PubSubTypeOf<Ours>::type ours_type;
  RosPubSub ros_type;
  EXPECT_EQ(ros_type.getName(), ros2_type_name(ours_type.getName()));
  EXPECT_EQ(ros_type.m_typeSize, ours_type.m_typeSize) << ros_type.getName();
  Ours copy = sample;
  const Bytes ours_bytes = serialize(ours_type, &copy);
  Ros ros_sample;
  deserialize(ros_type, ours_bytes, &ros_sample);
  check_by_name(ros_sample);
  EXPECT_EQ(serialize(ros_type, &ros_sample), ours_bytes) << ros_type.getName();
  Ours back;
  deserialize(ours_type, serialize(ros_type, &ros_sample), &back);
  EXPECT_TRUE(back == sample) << ros_type.getName();
}

void fill(msg::SampleHeader& h) {
  h.seq(7);
  h.stamp_ns(1'700'000'000'123'456'789);
  h.stamp_mono_ns(-5);
  h.source("node_a");
}
void expect_header(const ros::SampleHeader_& h) {
  EXPECT_EQ(h.seq_(), 7u);
  EXPECT_EQ(h.stamp_ns_(), 1'700'000'000'123'456'789);
  EXPECT_EQ(h.stamp_mono_ns_(), -5);
  EXPECT_EQ(h.source_().to_string(), "node_a");
}
void fill(msg::Pose& p) {
  p.position_m().x(1.5);
  p.position_m().y(-2.5);
  p.position_m().z(3.5);
  p.orientation().w(0.5);
  p.orientation().x(0.25);
  p.orientation().y(0.125);
  p.orientation().z(0.0625);
}
void fill(msg::Twist& t) {
  t.linear_mps().x(0.1);
  t.angular_radps().z(-0.3);
}

TEST(Ros2Wire, JointState) {
  msg::JointState s;
  fill(s.header());
  s.robot("panda");
  s.arm("left");
  s.q_rad({0.1, 0.2, 0.3});
  s.dq_radps({-1.0});
  s.tau_measured_nm({5, 6, 7, 8});
  s.tau_ext_nm({});
  expect_wire_identical<msg::JointState, ros::JointState_PubSubType, ros::JointState_>(
      s, [](const ros::JointState_& r) {
        expect_header(r.header_());
        EXPECT_EQ(r.robot_().to_string(), "panda");
        EXPECT_EQ(r.arm_().to_string(), "left");
        EXPECT_EQ(r.q_rad_(), (std::vector<double>{0.1, 0.2, 0.3}));
        EXPECT_EQ(r.dq_radps_(), (std::vector<double>{-1.0}));
        EXPECT_EQ(r.tau_measured_nm_(), (std::vector<double>{5, 6, 7, 8}));
        EXPECT_TRUE(r.tau_ext_nm_().empty());
      });
}

TEST(Ros2Wire, JointCommandModesAreUnsigned32BitIntegers) {
  msg::JointCommand s;
  fill(s.header());
  s.robot("ur");
  s.arm("right");
  s.mode({msg::CONTROL_GRAVITY, msg::CONTROL_POSITION_PD, msg::CONTROL_CARTESIAN_IMPEDANCE});
  s.q_des_rad({1, 2, 3});
  s.dq_des_radps({4, 5, 6});
  s.tau_ff_nm({7, 8, 9});
  s.stiffness_nm_per_rad({10, 11, 12});
  s.damping_nms_per_rad({13, 14, 15});
  expect_wire_identical<msg::JointCommand, ros::JointCommand_PubSubType, ros::JointCommand_>(
      s, [](const ros::JointCommand_& r) {
        EXPECT_EQ(r.mode_(), (std::vector<uint32_t>{ros::JointCommand_Constants::CONTROL_GRAVITY_,
                                                    ros::JointCommand_Constants::CONTROL_POSITION_PD_,
                                                    ros::JointCommand_Constants::CONTROL_CARTESIAN_IMPEDANCE_}));
        EXPECT_EQ(r.damping_nms_per_rad_(), (std::vector<double>{13, 14, 15}));
      });
}

TEST(Ros2Wire, CartesianCommandQuaternionIsScalarFirst) {
  msg::CartesianCommand s;
  fill(s.header());
  s.robot("panda");
  s.arm("left");
  s.frame("base");
  fill(s.target_pose());
  fill(s.target_twist());
  s.stiffness_translational_n_per_m().y(800);
  s.stiffness_rotational_nm_per_rad().z(30);
  s.damping_ratio(0.7);
  s.nullspace_stiffness_nm_per_rad(2);
  expect_wire_identical<msg::CartesianCommand, ros::CartesianCommand_PubSubType, ros::CartesianCommand_>(
      s, [](const ros::CartesianCommand_& r) {
        EXPECT_EQ(r.frame_().to_string(), "base");
        EXPECT_EQ(r.target_pose_().orientation_().w_(), 0.5);
        EXPECT_EQ(r.target_pose_().orientation_().z_(), 0.0625);
        EXPECT_EQ(r.target_twist_().angular_radps_().z_(), -0.3);
        EXPECT_EQ(r.damping_ratio_(), 0.7);
        EXPECT_EQ(r.nullspace_stiffness_nm_per_rad_(), 2);
      });
}

TEST(Ros2Wire, WrenchStampedAndJointTorque) {
  msg::WrenchStamped w;
  fill(w.header());
  w.frame("tcp");
  w.force_n().z(-9.81);
  w.torque_nm().x(0.5);
  expect_wire_identical<msg::WrenchStamped, ros::WrenchStamped_PubSubType, ros::WrenchStamped_>(
      w, [](const ros::WrenchStamped_& r) {
        EXPECT_EQ(r.force_n_().z_(), -9.81);
        EXPECT_EQ(r.torque_nm_().x_(), 0.5);
      });
  msg::JointTorque t;
  fill(t.header());
  t.robot("panda");
  t.arm("right");
  t.tau_nm({1, -1});
  expect_wire_identical<msg::JointTorque, ros::JointTorque_PubSubType, ros::JointTorque_>(
      t, [](const ros::JointTorque_& r) {
        EXPECT_EQ(r.tau_nm_(), (std::vector<double>{1, -1}));
      });
}

TEST(Ros2Wire, HandCommandAndHandStateFixedArrays) {
  msg::HandCommand c;
  fill(c.header());
  c.target_position_rad()[8] = 0.9;
  c.current_limit_a()[0] = 1.2;
  c.enable(true);
  c.fault_reset(false);
  expect_wire_identical<msg::HandCommand, ros::HandCommand_PubSubType, ros::HandCommand_>(
      c, [](const ros::HandCommand_& r) {
        EXPECT_EQ(r.target_position_rad_()[8], 0.9);
        EXPECT_TRUE(r.enable_());
        EXPECT_FALSE(r.fault_reset_());
      });
  msg::HandState s;
  fill(s.header());
  for (size_t m = 0; m < 9; ++m) {
    s.position_rad()[m] = 0.1 * static_cast<double>(m);
    s.statusword()[m] = static_cast<uint16_t>(0x0237 + m);
    s.error_code()[m] = static_cast<uint16_t>(m);
    s.faults()[m] = msg::HAND_FAULT_SDO >> m;
  }
  expect_wire_identical<msg::HandState, ros::HandState_PubSubType, ros::HandState_>(s, [](const ros::HandState_& r) {
    EXPECT_EQ(r.statusword_()[3], 0x023A);
    EXPECT_EQ(r.error_code_()[8], 8);
    EXPECT_EQ(r.faults_()[0], ros::HandState_Constants::HAND_FAULT_SDO_);
    EXPECT_EQ(r.position_rad_()[5], 0.5);
  });
}

TEST(Ros2Wire, NodeStatusEnumsAndNestedSequences) {
  msg::NodeStatus s;
  fill(s.header());
  s.role(msg::ROLE_TWIN);
  s.state(msg::STATE_SAFE_HOLD);
  s.fault_codes({msg::FAULT_PEER_LOST, msg::FAULT_SPEED_REFLEX});
  s.loop().rate_hz(999.5);
  s.loop().cycles(123456);
  s.loop().lateness_max_ns(-1);
  s.links().resize(1);
  s.links()[0].peer("follower");
  s.links()[0].delay_p99_ns(35'000'000);
  s.flows().resize(2);
  s.flows()[1].topic("teleop/follower/joint_state");
  s.flows()[1].awaited(true);
  s.flows()[1].writers(-1);
  s.tdpa_energy_j(0.25);
  s.can_bus_state("error_active");
  expect_wire_identical<msg::NodeStatus, ros::NodeStatus_PubSubType, ros::NodeStatus_>(
      s, [](const ros::NodeStatus_& r) {
        EXPECT_EQ(r.role_(), ros::NodeStatus_Constants::ROLE_TWIN_);
        EXPECT_EQ(r.state_(), ros::NodeStatus_Constants::STATE_SAFE_HOLD_);
        EXPECT_EQ(r.fault_codes_(), (std::vector<uint32_t>{1, 7}));
        EXPECT_EQ(r.loop_().cycles_(), 123456u);
        ASSERT_EQ(r.links_().size(), 1u);
        EXPECT_EQ(r.links_()[0].peer_().to_string(), "follower");
        EXPECT_EQ(r.links_()[0].delay_p99_ns_(), 35'000'000);
        ASSERT_EQ(r.flows_().size(), 2u);
        EXPECT_EQ(r.flows_()[1].topic_().to_string(), "teleop/follower/joint_state");
        EXPECT_EQ(r.flows_()[1].writers_(), -1);
        EXPECT_EQ(r.can_bus_state_().to_string(), "error_active");
      });
}

TEST(Ros2Wire, EmergencyStop) {
  msg::EmergencyStop q;
  fill(q.header());
  q.engaged(true);
  q.target("follower");
  q.origin("button 0 of the leader's device");
  expect_wire_identical<msg::EmergencyStop, ros::EmergencyStop_PubSubType, ros::EmergencyStop_>(
      q, [](const ros::EmergencyStop_& r) {
        EXPECT_TRUE(r.engaged_());
        EXPECT_EQ(r.target_().to_string(), "follower");
        EXPECT_EQ(r.origin_().to_string(), "button 0 of the leader's device");
      });
}

TEST(Ros2Wire, ResetRequestAndTdpaEnergy) {
  msg::ResetRequest q;
  fill(q.header());
  q.target("follower");
  expect_wire_identical<msg::ResetRequest, ros::ResetRequest_PubSubType, ros::ResetRequest_>(
      q, [](const ros::ResetRequest_& r) { EXPECT_EQ(r.target_().to_string(), "follower"); });
  msg::TdpaEnergy e;
  fill(e.header());
  e.session(3);
  e.energy_in_j({0.5, 0.25});
  e.energy_out_j({0.125});
  expect_wire_identical<msg::TdpaEnergy, ros::TdpaEnergy_PubSubType, ros::TdpaEnergy_>(
      e, [](const ros::TdpaEnergy_& r) {
        EXPECT_EQ(r.session_(), 3u);
        EXPECT_EQ(r.energy_out_j_(), (std::vector<double>{0.125}));
      });
}

TEST(Ros2Wire, GeomDistancesSequenceOfBoundedStringsAndObjectPose) {
  msg::GeomDistances d;
  fill(d.header());
  d.pair({msg::Name("hand_box"), msg::Name("arm_table")});
  d.distance_m({0.01, 0.2});
  expect_wire_identical<msg::GeomDistances, ros::GeomDistances_PubSubType, ros::GeomDistances_>(
      d, [](const ros::GeomDistances_& r) {
        ASSERT_EQ(r.pair_().size(), 2u);
        EXPECT_EQ(r.pair_()[1].to_string(), "arm_table");
      });
  msg::ObjectPose p;
  fill(p.header());
  p.body("box");
  fill(p.world_pose());
  fill(p.world_twist());
  expect_wire_identical<msg::ObjectPose, ros::ObjectPose_PubSubType, ros::ObjectPose_>(
      p, [](const ros::ObjectPose_& r) {
        EXPECT_EQ(r.body_().to_string(), "box");
        EXPECT_EQ(r.world_pose_().position_m_().y_(), -2.5);
      });
}

// A new sample type needs its message, and the package must build every message it has.
TEST(Ros2Wire, EverySampleTypeHasAMessageThePackageBuilds) {
  const std::filesystem::path package = std::filesystem::path(TELEOP_SOURCE_DIR) / "idl/ros2/teleop_msgs";
  std::ifstream cmake(package / "CMakeLists.txt");
  const std::string listed((std::istreambuf_iterator<char>(cmake)), std::istreambuf_iterator<char>());
  for (const SampleType& type : sample_types()) {
    const std::string leaf = type.dds_name.substr(type.dds_name.rfind(':') + 1);
    EXPECT_TRUE(std::filesystem::exists(package / "msg" / (leaf + ".msg"))) << leaf;
  }
  int messages = 0;
  for (const auto& entry : std::filesystem::directory_iterator(package / "msg")) {
    ++messages;
    EXPECT_NE(listed.find("  msg/" + entry.path().filename().string()), std::string::npos)
        << entry.path().filename() << " is not in the package's CMakeLists.txt";
  }
  EXPECT_GE(messages, static_cast<int>(sample_types().size()));
}

}  // namespace
}  // namespace teleop::transport
