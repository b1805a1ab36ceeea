// Who is on the bus, from discovery's reports.
#include <gtest/gtest.h>

#include "teleop/tools/topic_graph.h"

namespace teleop::tools {
namespace {

transport::ParticipantInfo participant(uint8_t id, const char* name) {
  transport::ParticipantInfo p;
  p.id[0] = id;
  p.name = name;
  p.host = "robot-pc";
  return p;
}

transport::EndpointInfo endpoint(uint8_t participant, uint8_t entity, bool writer, const char* topic) {
  transport::EndpointInfo e;
  e.guid.bytes[0] = participant;
  e.guid.bytes[15] = entity;
  e.is_writer = writer;
  e.topic = topic;
  e.type = "teleop::msg::JointCommand";
  e.deadline_ns = 5'000'000;
  return e;
}

TEST(TopicGraph, GroupsEndpointsByTopicWithTheirNodesAndLeavesOutItsOwn) {
  TopicGraph graph;
  graph.on_participant(participant(1, "leader"), true);
  graph.on_participant(participant(2, "follower"), true);
  graph.on_endpoint(endpoint(1, 1, true, "teleop/leader/joint_command"), true);
  graph.on_endpoint(endpoint(2, 1, false, "teleop/leader/joint_command"), true);
  graph.on_endpoint(endpoint(9, 1, false, "teleop/leader/joint_command"), true);  // the tool itself
  transport::ParticipantId self{};
  self[0] = 9;
  const auto topics = graph.topics(self);
  ASSERT_EQ(topics.size(), 1u);
  EXPECT_EQ(topics[0].writers.size(), 1u);
  ASSERT_EQ(topics[0].readers.size(), 1u);
  EXPECT_EQ(topics[0].readers[0].node, "follower");
  const std::string list = format_topic_list(topics, true);
  EXPECT_NE(list.find("teleop/leader/joint_command"), std::string::npos) << list;
  EXPECT_NE(list.find("1 writer, 1 reader  (from leader to follower)"), std::string::npos) << list;
  const std::string info = format_topic_info(topics[0]);
  EXPECT_NE(info.find("type: teleop::msg::JointCommand"), std::string::npos) << info;
  EXPECT_NE(info.find("node: leader (host robot-pc)\n    qos: best effort, volatile, deadline 5 ms"), std::string::npos)
      << info;
}

TEST(TopicGraph, ForgetsAParticipantsEndpointsWhenItLeaves) {
  TopicGraph graph;
  graph.on_participant(participant(1, "leader"), true);
  graph.on_endpoint(endpoint(1, 1, true, "teleop/leader/joint_command"), true);
  graph.on_participant(participant(1, "leader"), false);
  EXPECT_TRUE(graph.topics({}).empty());
  EXPECT_TRUE(graph.participants().empty());
}

}  // namespace
}  // namespace teleop::tools
