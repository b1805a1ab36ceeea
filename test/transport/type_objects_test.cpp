// The types are built with XTypes type objects (fastddsgen -typeobject): a participant registers
// them, its writers and readers announce neither them nor their type information in discovery
// (docs/transport.md), the objects describe the bytes on the wire (a dynamic type built from them
// reads a sample), and registering them never makes a sample's construction allocate (the control
// loop constructs sequence elements).

#include <fastrtps/types/DynamicData.h>
#include <fastrtps/types/DynamicDataFactory.h>
#include <fastrtps/types/DynamicPubSubType.h>
#include <fastrtps/types/TypeObjectFactory.h>
#include <gtest/gtest.h>
#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/domain/DomainParticipantListener.hpp>

#include <atomic>
#include <string>

#include "allocation_counter.h"
#include "in_process_bus.h"
#include "teleop/transport/participant.h"
#include "teleop/transport/sample_types.h"

namespace teleop::transport {
namespace {

namespace dds = eprosima::fastdds::dds;
using eprosima::fastrtps::types::TypeObjectFactory;

using test_bus::config;
using test_bus::wait_for;

TEST(TypeObjects, AParticipantRegistersThoseOfEverySampleType) {
  Participant p(config("type_objects"));
  auto* factory = TypeObjectFactory::get_instance();
  for (const SampleType& type : sample_types()) {
    EXPECT_NE(factory->get_type_object(type.dds_name, true), nullptr) << type.dds_name << " (complete)";
    EXPECT_NE(factory->get_type_object(type.dds_name, false), nullptr) << type.dds_name << " (minimal)";
    EXPECT_NE(factory->get_type_information(type.dds_name), nullptr) << type.dds_name;
  }
}

template <typename T>
uint64_t allocations_of_a_construction() {
  { T first; }  // registers its file's type objects, once
  test::ScopedAllocationCounter counter;
  T sample;
  return counter.count();
}

TEST(TypeObjects, ConstructingASampleDoesNotAllocate) {
  EXPECT_EQ(allocations_of_a_construction<msg::JointState>(), 0u);
  EXPECT_EQ(allocations_of_a_construction<msg::JointCommand>(), 0u);
  EXPECT_EQ(allocations_of_a_construction<msg::CartesianCommand>(), 0u);
  EXPECT_EQ(allocations_of_a_construction<msg::WrenchStamped>(), 0u);
  EXPECT_EQ(allocations_of_a_construction<msg::JointTorque>(), 0u);
  EXPECT_EQ(allocations_of_a_construction<msg::HandCommand>(), 0u);
  EXPECT_EQ(allocations_of_a_construction<msg::HandState>(), 0u);
  EXPECT_EQ(allocations_of_a_construction<msg::NodeStatus>(), 0u);
  EXPECT_EQ(allocations_of_a_construction<msg::LinkStatistics>(), 0u);  // emplaced per status
  EXPECT_EQ(allocations_of_a_construction<msg::FlowStatus>(), 0u);
  EXPECT_EQ(allocations_of_a_construction<msg::ResetRequest>(), 0u);
  EXPECT_EQ(allocations_of_a_construction<msg::TdpaEnergy>(), 0u);
  EXPECT_EQ(allocations_of_a_construction<msg::GeomDistances>(), 0u);
  EXPECT_EQ(allocations_of_a_construction<msg::ObjectPose>(), 0u);
  EXPECT_EQ(allocations_of_a_construction<msg::EmergencyStop>(), 0u);
}

TEST(TypeObjects, DescribeTheBytesOnTheWire) {
  register_type_objects();
  msg::JointState s;
  s.header().seq(42);
  s.robot("panda");
  s.q_rad({0.5, -0.25});
  PubSubTypeOf<msg::JointState>::type ours;
  eprosima::fastrtps::rtps::SerializedPayload_t payload(ours.m_typeSize);
  ASSERT_TRUE(ours.serialize(&s, &payload));

  // what a tool that has no teleop code makes of the type object
  auto* factory = TypeObjectFactory::get_instance();
  const std::string name = "teleop::msg::JointState";
  auto dynamic_type =
      factory->build_dynamic_type(name, factory->get_type_identifier(name, true), factory->get_type_object(name, true));
  ASSERT_TRUE(dynamic_type);
  eprosima::fastrtps::types::DynamicPubSubType dynamic(dynamic_type);
  auto* data = eprosima::fastrtps::types::DynamicDataFactory::get_instance()->create_data(dynamic_type);
  ASSERT_TRUE(dynamic.deserialize(&payload, data));
  EXPECT_EQ(data->get_string_value(data->get_member_id_by_name("robot")), "panda");
  auto* header = data->loan_value(data->get_member_id_by_name("header"));
  ASSERT_NE(header, nullptr);
  EXPECT_EQ(header->get_uint64_value(header->get_member_id_by_name("seq")), 42u);
  data->return_loaned_value(header);
  auto* q = data->loan_value(data->get_member_id_by_name("q_rad"));
  ASSERT_NE(q, nullptr);
  ASSERT_EQ(q->get_item_count(), 2u);
  EXPECT_EQ(q->get_float64_value(1), -0.25);
  data->return_loaned_value(q);
  eprosima::fastrtps::types::DynamicDataFactory::get_instance()->delete_data(data);
}

// Hears what the discovered endpoints of `topic` announce of their type. Neither may announce
// anything: Fast DDS 2.9 crashes building a dynamic type from a type object it does not know (the
// discovery server did), and Cyclone DDS drops every endpoint with Fast DDS 2.9's type information
// (participant.cpp); cyclone_interop_test.cpp proves the matching itself.
class TypeAnnouncements : public dds::DomainParticipantListener {
 public:
  explicit TypeAnnouncements(std::string topic) : topic_(std::move(topic)) {}
  void on_publisher_discovery(dds::DomainParticipant*, eprosima::fastrtps::rtps::WriterDiscoveryInfo&& info) override {
    if (info.info.topicName().to_string() == topic_) hear(writer, info.info);
  }
  void on_subscriber_discovery(dds::DomainParticipant*, eprosima::fastrtps::rtps::ReaderDiscoveryInfo&& info) override {
    if (info.info.topicName().to_string() == topic_) hear(reader, info.info);
  }

  struct Heard {
    std::atomic<bool> seen{false};
    std::atomic<bool> type_information{false};
    std::atomic<bool> type_object{false};
  };
  Heard writer;
  Heard reader;

 private:
  // WriterProxyData and ReaderProxyData have the same accessors, and no common base that has them
  template <typename ProxyData>
  static void hear(Heard& heard, const ProxyData& data) {
    heard.type_information = data.has_type_information() && data.type_information().assigned();
    heard.type_object = data.has_type() && data.type().m_type_object._d() != 0;
    heard.seen = true;
  }
  std::string topic_;
};

TEST(TypeObjects, EndpointsAnnounceNeitherTypeInformationNorTypeObjectInDiscovery) {
  const std::string topic = test_bus::topic_name("typed");
  TypeAnnouncements announcements(topic);
  auto* factory = dds::DomainParticipantFactory::get_instance();
  dds::DomainParticipant* observer = factory->create_participant(static_cast<dds::DomainId_t>(test_bus::domain()),
                                                                 dds::PARTICIPANT_QOS_DEFAULT, &announcements);
  ASSERT_NE(observer, nullptr);
  {
    Participant p(config("typed_endpoints"));
    const Writer<msg::JointState> writer = p.make_writer(TopicSpec<msg::JointState>{topic.c_str(), QosPreset::kStream});
    const Reader<msg::JointState> reader = p.make_reader(TopicSpec<msg::JointState>{topic.c_str(), QosPreset::kStream});
    EXPECT_TRUE(writer.valid());
    EXPECT_TRUE(reader.valid());
    EXPECT_TRUE(wait_for([&] { return announcements.writer.seen.load() && announcements.reader.seen.load(); }));
    EXPECT_FALSE(announcements.writer.type_information.load());
    EXPECT_FALSE(announcements.writer.type_object.load());
    EXPECT_FALSE(announcements.reader.type_information.load());
    EXPECT_FALSE(announcements.reader.type_object.load());
  }
  factory->delete_participant(observer);
}

}  // namespace
}  // namespace teleop::transport
