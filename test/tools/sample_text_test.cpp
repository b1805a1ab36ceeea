// Any teleop sample as YAML from its serialized bytes; one field of it; its header in place.
#include <gtest/gtest.h>

#include "serialized_sample.h"
#include "teleop/tools/sample_text.h"

namespace teleop::tools {
namespace {

msg::JointState joint_state() {
  msg::JointState s;
  s.header().seq(42);
  s.header().stamp_ns(1'700'000'000'000'000'000);
  s.header().stamp_mono_ns(123);
  s.header().source("follower");
  s.robot("panda");
  s.arm("right");
  s.q_rad({0.5, -1.25});
  return s;
}

TEST(SampleText, PrintsAJointStateAsYaml) {
  const std::string text = sample_text(type_of<msg::JointState>(), serialize(joint_state()));
  EXPECT_NE(text.find("header:\n  seq: 42\n  stamp_ns: 1700000000000000000\n"), std::string::npos) << text;
  EXPECT_NE(text.find("  source: follower\n"), std::string::npos) << text;
  EXPECT_NE(text.find("robot: panda\n"), std::string::npos) << text;
  EXPECT_NE(text.find("q_rad: [0.5, -1.25]\n"), std::string::npos) << text;
  EXPECT_NE(text.find("dq_radps: []\n"), std::string::npos) << text;
}

TEST(SampleText, PrintsOneFieldByItsPath) {
  const auto cdr = serialize(joint_state());
  EXPECT_EQ(sample_text(type_of<msg::JointState>(), cdr, "header.seq"), "42\n");
  EXPECT_EQ(sample_text(type_of<msg::JointState>(), cdr, "q_rad"), "[0.5, -1.25]\n");
  EXPECT_EQ(sample_text(type_of<msg::JointState>(), cdr, "header").substr(0, 8), "seq: 42\n");
}

TEST(SampleText, AFieldThatDoesNotExistIsAnErrorNamingIt) {
  try {
    sample_text(type_of<msg::JointState>(), serialize(joint_state()), "q_deg");
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("no field 'q_deg'"), std::string::npos) << e.what();
  }
}

TEST(SampleText, ListsOfStructsAreYamlSequences) {
  msg::NodeStatus s;
  s.header().source("leader");
  s.state(msg::STATE_SAFE_HOLD);
  s.fault_codes({msg::FAULT_PEER_LOST});
  s.links().emplace_back();
  s.links().back().peer("follower");
  s.links().back().lost(7);
  s.flows().emplace_back();
  s.flows().back().topic("teleop/follower/joint_state");
  s.flows().back().awaited(true);
  s.flows().back().writers(0);
  const auto cdr = serialize(s);
  const std::string text = sample_text(type_of<msg::NodeStatus>(), cdr);
  EXPECT_NE(text.find("state: safe_hold\n"), std::string::npos) << text;
  EXPECT_NE(text.find("fault_codes: [peer_lost]\n"), std::string::npos) << text;
  EXPECT_NE(text.find("links:\n  - peer: follower\n    profile: \n"), std::string::npos) << text;
  EXPECT_NE(text.find("flows:\n  - topic: teleop/follower/joint_state\n    awaited: true\n    writers: 0\n"),
            std::string::npos)
      << text;
  EXPECT_EQ(sample_text(type_of<msg::NodeStatus>(), cdr, "links[0].lost"), "7\n");
}

TEST(SampleText, BytesThatAreNoSampleOfTheTypeAreAnError) {
  std::vector<uint8_t> cdr = serialize(joint_state());
  cdr.resize(30);
  EXPECT_THROW(sample_text(type_of<msg::JointState>(), cdr), std::runtime_error);
}

TEST(SampleHeader, IsReadAndRestampedInPlaceForEveryType) {
  std::vector<uint8_t> cdr = serialize(joint_state());
  HeaderView h;
  ASSERT_TRUE(read_header(cdr, h));
  EXPECT_EQ(h.seq, 42u);
  EXPECT_EQ(h.stamp_ns, 1'700'000'000'000'000'000);
  EXPECT_EQ(h.stamp_mono_ns, 123);
  ASSERT_TRUE(restamp_header(cdr, 5, 6));
  EXPECT_EQ(sample_text(type_of<msg::JointState>(), cdr, "header.stamp_ns"), "5\n");
  EXPECT_EQ(sample_text(type_of<msg::JointState>(), cdr, "header.stamp_mono_ns"), "6\n");
  EXPECT_EQ(sample_text(type_of<msg::JointState>(), cdr, "header.seq"), "42\n");
  msg::HandCommand hand;
  hand.header().seq(9);
  ASSERT_TRUE(read_header(serialize(hand), h));
  EXPECT_EQ(h.seq, 9u);
  EXPECT_FALSE(read_header(std::vector<uint8_t>(10, 0), h));
}

TEST(SampleTypes, KnowsEveryTypeByItsDdsAndItsRosName) {
  EXPECT_EQ(transport::sample_types().size(), 13u);
  const transport::SampleType* t = transport::find_sample_type("teleop/msg/JointCommand");
  ASSERT_NE(t, nullptr);
  EXPECT_EQ(t->dds_name, "teleop::msg::JointCommand");
  EXPECT_EQ(transport::find_sample_type("std_msgs::msg::String"), nullptr);
  EXPECT_EQ(transport::topic_qos("teleop/node_status"), transport::QosPreset::kState);
  EXPECT_EQ(transport::topic_qos("teleop/follower/object_pose/box"), transport::QosPreset::kStream);
}

}  // namespace
}  // namespace teleop::tools
