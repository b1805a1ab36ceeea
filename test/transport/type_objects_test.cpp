// The types are built with XTypes type objects (fastddsgen -typeobject): a participant registers
// them, writers announce their type information (not the objects) in discovery, the objects
// describe the bytes on the wire (a dynamic type built from them reads a sample), and registering
// them never makes a sample's construction allocate (the control loop constructs sequence elements).

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

// Hears whether a discovered writer of `topic` announced its type information (the hashes) and
// whether it sent the type object itself (it must not: Fast DDS 2.9 crashes building a dynamic
// type from one it does not know, the discovery server among them; participant.cpp).
class TypeAnnouncements : public dds::DomainParticipantListener {
 public:
  explicit TypeAnnouncements(std::string topic) : topic_(std::move(topic)) {}
  void on_publisher_discovery(dds::DomainParticipant*, eprosima::fastrtps::rtps::WriterDiscoveryInfo&& info) override {
    if (info.info.topicName().to_string() != topic_) return;
    seen = true;
    announced = info.info.has_type_information() && info.info.type_information().assigned();
    object_sent = info.info.has_type() && info.info.type().m_type_object._d() != 0;
  }
  std::atomic<bool> seen{false};
  std::atomic<bool> announced{false};
  std::atomic<bool> object_sent{false};

 private:
  std::string topic_;
};

TEST(TypeObjects, WritersAnnounceTheirTypeInformationButNotTheTypeObjectInDiscovery) {
  const std::string topic = test_bus::topic_name("typed");
  TypeAnnouncements announcements(topic);
  auto* factory = dds::DomainParticipantFactory::get_instance();
  dds::DomainParticipant* observer = factory->create_participant(static_cast<dds::DomainId_t>(test_bus::domain()),
                                                                 dds::PARTICIPANT_QOS_DEFAULT, &announcements);
  ASSERT_NE(observer, nullptr);
  {
    Participant p(config("typed_writer"));
    const Writer<msg::JointState> writer = p.make_writer(TopicSpec<msg::JointState>{topic.c_str(), QosPreset::kStream});
    EXPECT_TRUE(writer.valid());
    EXPECT_TRUE(wait_for([&] { return announcements.seen.load(); }));
    EXPECT_TRUE(announcements.announced.load());
    EXPECT_FALSE(announcements.object_sent.load());
  }
  factory->delete_participant(observer);
}

}  // namespace
}  // namespace teleop::transport
