// The ROS 2 messages the `ros2` backend speaks are what ROS 2 puts on the wire: each serialized by
// teleop (fastddsgen's types of idl/ros2/common_interfaces, teleop::ros2_msgs) and by Cyclone DDS
// (idlc's types of the same IDL, Cyclone's CDR writer: cyclone_wire.h), byte for byte, with
// strings and sequences of every length parity so that each alignment rule is exercised.
#include <gtest/gtest.h>

#include <fastdds/rtps/common/SerializedPayload.h>

#include <cmath>

#include "cyclone_wire.h"
#include "geometry_msgs/msg/WrenchStamped_PubSubTypes.h"
#include "sensor_msgs/msg/JointState_PubSubTypes.h"
#include "std_msgs/msg/Float64MultiArray_PubSubTypes.h"

namespace teleop::robot {
namespace {

// teleop's bytes of `m`, after checking the encapsulation header says plain CDR, little endian
template <typename PubSubType, typename Msg>
std::vector<uint8_t> teleop_cdr(Msg& m) {
  PubSubType type;
  eprosima::fastrtps::rtps::SerializedPayload_t payload(type.getSerializedSizeProvider(&m)());
  EXPECT_TRUE(type.serialize(&m, &payload));
  EXPECT_EQ(payload.data[0], 0x00);
  EXPECT_EQ(payload.data[1], 0x01) << "CDR_LE";
  return {payload.data + 4, payload.data + payload.length};
}

template <typename H>
void fill_header(H& h, const cyclone::Stamp& s) {
  h.stamp_().sec_(s.sec);
  h.stamp_().nanosec_(s.nanosec);
  h.frame_id_(s.frame_id);
}

class Ros2Wire : public ::testing::TestWithParam<size_t> {};

TEST_P(Ros2Wire, JointStateIsCyclonesByteForByte) {
  const size_t n = GetParam();
  cyclone::JointStateValues v;
  v.header = {1'764'300'000, 123'456'789, n % 2 ? "base" : "fr3_link0"};
  for (size_t i = 0; i < n; ++i) {
    v.names.push_back("fr3_joint" + std::string(i + 1, 'x'));  // names of every length
    v.position.push_back(0.1 * static_cast<double>(i) - 0.35);
    v.velocity.push_back(-1e-3 * static_cast<double>(i));
    if (n != 3) v.effort.push_back(std::ldexp(1.0, static_cast<int>(i)));  // empty effort too
  }
  sensor_msgs::msg::dds_::JointState_ s;
  fill_header(s.header_(), v.header);
  s.name_(v.names);
  s.position_(v.position);
  s.velocity_(v.velocity);
  s.effort_(v.effort);
  EXPECT_EQ(teleop_cdr<sensor_msgs::msg::dds_::JointState_PubSubType>(s), cyclone::cdr(v));
}

TEST_P(Ros2Wire, Float64MultiArrayIsCyclonesByteForByte) {
  const size_t n = GetParam();
  cyclone::MultiArrayValues v;
  if (n % 2) v.dims.push_back({"joints", static_cast<uint32_t>(n), static_cast<uint32_t>(n)});
  if (n > 4) v.dims.push_back({"x", 1, 1});
  v.data_offset = static_cast<uint32_t>(n % 3);
  for (size_t i = 0; i < n; ++i) v.data.push_back(12.5 - static_cast<double>(i));
  std_msgs::msg::dds_::Float64MultiArray_ m;
  for (const auto& d : v.dims) {
    std_msgs::msg::dds_::MultiArrayDimension_ dim;
    dim.label_(d.label);
    dim.size_(d.size);
    dim.stride_(d.stride);
    m.layout_().dim_().push_back(dim);
  }
  m.layout_().data_offset_(v.data_offset);
  m.data_(v.data);
  EXPECT_EQ(teleop_cdr<std_msgs::msg::dds_::Float64MultiArray_PubSubType>(m), cyclone::cdr(v));
}

TEST_P(Ros2Wire, WrenchStampedIsCyclonesByteForByte) {
  const size_t n = GetParam();
  cyclone::WrenchValues v;
  v.header = {-1, 999'999'999, std::string(n, 'f')};
  v.force = {1.5, -2.25, static_cast<double>(n)};
  v.torque = {0.125, 0.0, -7.0};
  geometry_msgs::msg::dds_::WrenchStamped_ w;
  fill_header(w.header_(), v.header);
  w.wrench_().force_().x_(v.force[0]);
  w.wrench_().force_().y_(v.force[1]);
  w.wrench_().force_().z_(v.force[2]);
  w.wrench_().torque_().x_(v.torque[0]);
  w.wrench_().torque_().y_(v.torque[1]);
  w.wrench_().torque_().z_(v.torque[2]);
  EXPECT_EQ(teleop_cdr<geometry_msgs::msg::dds_::WrenchStamped_PubSubType>(w), cyclone::cdr(v));
}

// 0 (empty sequences and strings), odd and even counts, a Franka's 7 and a hand's 9
INSTANTIATE_TEST_SUITE_P(Lengths, Ros2Wire, ::testing::Values(0u, 1u, 2u, 3u, 6u, 7u, 9u));

}  // namespace
}  // namespace teleop::robot
