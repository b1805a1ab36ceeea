// `naming: ros2` on the wire: a plain Fast DDS reader that knows only ROS 2's names (topic
// "rt/...", type "teleop_msgs::msg::dds_::JointState_", the type ROS 2 makes of teleop_msgs)
// receives what a teleop node writes, a ROS 2 style writer reaches a teleop node, and the bus
// tools see the topics under their teleop names.

#include <gtest/gtest.h>
#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>

#include <mutex>
#include <set>
#include <string>
#include <vector>

#include "discovery_listener.h"
#include "in_process_bus.h"
#include "teleop/transport/participant.h"
#include "teleop/transport/publication.h"
#include "teleop/transport/subscription.h"
#include "teleop_msgs/JointState_PubSubTypes.h"

namespace teleop::transport {
namespace {

namespace dds = eprosima::fastdds::dds;
namespace ros = teleop_msgs::msg::dds_;
using eprosima::fastrtps::types::ReturnCode_t;

using test_bus::stream_topic;
using test_bus::topic_name;
using test_bus::wait_for;

ParticipantConfig config(const std::string& name, Naming naming) {
  ParticipantConfig c = test_bus::config(name);
  c.naming = naming;
  return c;
}

// A participant with nothing of teleop: what a ROS 2 node's rmw_fastrtps does, by hand.
class RosSide {
 public:
  explicit RosSide(const std::string& leaf) {
    auto* factory = dds::DomainParticipantFactory::get_instance();
    participant_ =
        factory->create_participant(static_cast<dds::DomainId_t>(test_bus::domain()), dds::PARTICIPANT_QOS_DEFAULT);
    dds::TypeSupport type(new ros::JointState_PubSubType());
    EXPECT_EQ(type.register_type(participant_), ReturnCode_t::RETCODE_OK);
    topic_ = participant_->create_topic("rt/" + topic_name(leaf), "teleop_msgs::msg::dds_::JointState_",
                                        dds::TOPIC_QOS_DEFAULT);
  }
  ~RosSide() {
    participant_->delete_contained_entities();
    dds::DomainParticipantFactory::get_instance()->delete_participant(participant_);
  }
  RosSide(const RosSide&) = delete;
  RosSide& operator=(const RosSide&) = delete;

  // rclcpp's SensorDataQoS: best effort, volatile, keep last 5 (no deadline, automatic liveliness)
  dds::DataReader* sensor_data_reader() {
    dds::DataReaderQos qos = dds::DATAREADER_QOS_DEFAULT;
    qos.reliability().kind = dds::BEST_EFFORT_RELIABILITY_QOS;
    qos.durability().kind = dds::VOLATILE_DURABILITY_QOS;
    qos.history().kind = dds::KEEP_LAST_HISTORY_QOS;
    qos.history().depth = 5;
    return participant_->create_subscriber(dds::SUBSCRIBER_QOS_DEFAULT)->create_datareader(topic_, qos);
  }
  // a publisher into a teleop stream must offer what its readers request (docs/transport.md)
  dds::DataWriter* stream_writer() {
    return participant_->create_publisher(dds::PUBLISHER_QOS_DEFAULT)
        ->create_datawriter(topic_, writer_qos(QosPreset::kStream, ParticipantConfig{}));
  }

 private:
  dds::DomainParticipant* participant_ = nullptr;
  dds::Topic* topic_ = nullptr;
};

TEST(Ros2Naming, ReaderWithRos2NamesReceivesWhatANodeWrites) {
  Participant node(config("ros2_writer_node", Naming::kRos2));
  Publication<msg::JointState> pub(node, stream_topic("to_ros"), "follower");
  RosSide ros_side("to_ros");
  dds::DataReader* reader = ros_side.sensor_data_reader();
  ASSERT_NE(reader, nullptr);
  ASSERT_TRUE(wait_for([&] {
    dds::SubscriptionMatchedStatus status;
    reader->get_subscription_matched_status(status);
    return pub.matched() == 1 && status.current_count == 1;
  })) << "a reader of rt/"
      << stream_topic("to_ros").name << " did not match the node's writer";

  for (int i = 1; i <= 5; ++i) {
    pub.sample().robot("panda");
    pub.sample().arm("left");
    pub.sample().q_rad({0.1 * i, 0.2 * i});
    pub.sample().tau_ext_nm({-1.0 * i});
    ASSERT_TRUE(pub.publish());
    ros::JointState_ received;
    dds::SampleInfo info;
    ASSERT_TRUE(wait_for([&] { return reader->take_next_sample(&received, &info) == ReturnCode_t::RETCODE_OK; }))
        << "sample " << i;
    EXPECT_EQ(received.header_().seq_(), static_cast<uint64_t>(i));
    EXPECT_EQ(received.header_().source_().to_string(), "follower");
    EXPECT_GT(received.header_().stamp_ns_(), 0);
    EXPECT_EQ(received.robot_().to_string(), "panda");
    EXPECT_EQ(received.arm_().to_string(), "left");
    EXPECT_EQ(received.q_rad_(), (std::vector<double>{0.1 * i, 0.2 * i}));
    EXPECT_TRUE(received.dq_radps_().empty());
    EXPECT_EQ(received.tau_ext_nm_(), (std::vector<double>{-1.0 * i}));
  }
}

TEST(Ros2Naming, NodeReadsWhatAWriterWithRos2NamesSends) {
  Participant node(config("ros2_reader_node", Naming::kRos2));
  Subscription<msg::JointState> sub(node, stream_topic("from_ros"));
  RosSide ros_side("from_ros");
  dds::DataWriter* writer = ros_side.stream_writer();
  ASSERT_NE(writer, nullptr);
  ASSERT_TRUE(wait_for([&] {
    dds::PublicationMatchedStatus status;
    writer->get_publication_matched_status(status);
    return sub.reader().matched() == 1 && status.current_count == 1;
  }));
  ros::JointState_ sample;
  sample.header_().seq_(1);
  sample.header_().source_("ros_node");
  sample.robot_("ur5e");
  sample.q_rad_({1.0, 2.0, 3.0});
  ASSERT_EQ(writer->write(&sample), true);
  ASSERT_TRUE(wait_for([&] { return sub.poll() > 0; }));
  EXPECT_EQ(sub.latest().header().source().to_string(), "ros_node");
  EXPECT_EQ(sub.latest().robot().to_string(), "ur5e");
  EXPECT_EQ(sub.latest().q_rad(), (std::vector<double>{1.0, 2.0, 3.0}));
}

TEST(Ros2Naming, ToolsSeeTopicsUnderTheirTeleopNamesAndEchoThem) {
  test_bus::DiscoveredWriters topics;  // what `teleop topic list` hears
  Participant tool(config("ros2_tool", Naming::kRos2), &topics);
  Participant node(config("ros2_node", Naming::kRos2));
  Publication<msg::JointState> pub(node, stream_topic("listed"), "follower");
  const std::string listed = stream_topic("listed").name;
  ASSERT_TRUE(wait_for([&] { return topics.by_topic().count(listed) == 1; }));
  EXPECT_EQ(topics.by_topic().at(listed).type, "teleop_msgs::msg::dds_::JointState_");
  EXPECT_EQ(topics.by_topic().count("rt/" + listed), 0u);

  // echo: a raw reader of the type found by its discovered name
  const SampleType* type = find_sample_type(topics.by_topic().at(listed).type);
  ASSERT_NE(type, nullptr);
  EXPECT_EQ(type->dds_name, "teleop::msg::JointState");
  std::mutex mutex;
  std::set<size_t> sizes;
  tool.make_raw_reader(listed, *type, QosPreset::kStream, [&](const RawSample& s) {
    std::lock_guard lock(mutex);
    sizes.insert(s.cdr.size());
  });
  ASSERT_TRUE(wait_for([&] { return pub.matched() == 1; }));
  ASSERT_TRUE(pub.publish());
  ASSERT_TRUE(wait_for([&] {
    std::lock_guard lock(mutex);
    return !sizes.empty();
  }));
}

// The discovery listener itself, fed what Fast DDS would report: under ros2 naming only the
// "rt/" topics are teleop's, under their names without the prefix.
std::vector<std::string> reported_topics(Naming naming, const std::vector<std::string>& dds_topics) {
  test_bus::DiscoveredWriters topics;
  DiscoveryListener listener(nullptr, &topics, naming);
  for (size_t i = 0; i < dds_topics.size(); ++i) {
    eprosima::fastrtps::rtps::WriterProxyData data(4, 4);
    data.topicName(dds_topics[i]);
    data.typeName("teleop_msgs::msg::dds_::JointState_");
    data.guid().entityId.value[3] = static_cast<uint8_t>(i + 1);
    listener.on_publisher_discovery(nullptr, eprosima::fastrtps::rtps::WriterDiscoveryInfo(data));
  }
  std::vector<std::string> names;
  for (const auto& [topic, writer] : topics.by_topic()) names.push_back(topic);
  return names;
}

TEST(Ros2Naming, DiscoveryReportsOnlyTheNamingsTopicsUnderTheirTeleopNames) {
  const std::vector<std::string> dds = {"rt/teleop/follower/joint_state", "rq/teleop/reset_serviceRequest",
                                        "teleop/twin/joint_state"};
  EXPECT_EQ(reported_topics(Naming::kRos2, dds), (std::vector<std::string>{"teleop/follower/joint_state"}));
  EXPECT_EQ(reported_topics(Naming::kPlain, dds),
            (std::vector<std::string>{"rq/teleop/reset_serviceRequest", "rt/teleop/follower/joint_state",
                                      "teleop/twin/joint_state"}));
}

}  // namespace
}  // namespace teleop::transport
