#include "bare_dds.h"

#include <fastdds/dds/core/status/PublicationMatchedStatus.hpp>
#include <fastdds/dds/core/status/SubscriptionMatchedStatus.hpp>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/Topic.hpp>
#include <fastdds/rtps/transport/UDPv4TransportDescriptor.h>

#include <stdexcept>

#include "teleop/transport/type_support.h"

namespace teleop::bench {
namespace dds = eprosima::fastdds::dds;
using eprosima::fastrtps::types::ReturnCode_t;

struct BareDds::ReaderListener : dds::DataReaderListener {
  ReaderListener(int i, OnSample cb) : topic(i), on_sample(std::move(cb)) {}
  void on_data_available(dds::DataReader* reader) override {
    dds::SampleInfo info;
    while (reader->take_next_sample(&sample, &info) == ReturnCode_t::RETCODE_OK) {
      if (info.valid_data) on_sample(topic, sample);
    }
  }
  int topic;
  OnSample on_sample;
  msg::JointState sample;
};

BareDds::BareDds(int domain, const std::vector<std::string>& write_topics, const std::vector<std::string>& read_topics,
                 OnSample on_sample) {
  dds::DomainParticipantQos pqos = dds::PARTICIPANT_QOS_DEFAULT;
  pqos.transport().use_builtin_transports = false;
  pqos.transport().user_transports.push_back(std::make_shared<eprosima::fastdds::rtps::UDPv4TransportDescriptor>());
  participant_ = dds::DomainParticipantFactory::get_instance()->create_participant(domain, pqos);
  if (participant_ == nullptr) throw std::runtime_error("bare Fast DDS: no participant");
  dds::TypeSupport type(new transport::PubSubTypeOf<msg::JointState>::type());
  type.register_type(participant_);
  auto* publisher = participant_->create_publisher(dds::PUBLISHER_QOS_DEFAULT);
  auto* subscriber = participant_->create_subscriber(dds::SUBSCRIBER_QOS_DEFAULT);
  if (publisher == nullptr || subscriber == nullptr) throw std::runtime_error("bare Fast DDS: no publisher/subscriber");

  dds::DataWriterQos wqos = dds::DATAWRITER_QOS_DEFAULT;
  wqos.reliability().kind = dds::BEST_EFFORT_RELIABILITY_QOS;
  wqos.history().kind = dds::KEEP_LAST_HISTORY_QOS;
  wqos.history().depth = 1;
  wqos.data_sharing().off();
  for (const auto& name : write_topics) {
    auto* topic = participant_->create_topic(name, type.get_type_name(), dds::TOPIC_QOS_DEFAULT);
    auto* writer = topic != nullptr ? publisher->create_datawriter(topic, wqos) : nullptr;
    if (writer == nullptr) throw std::runtime_error("bare Fast DDS: no writer on " + name);
    writers_.push_back(writer);
  }

  dds::DataReaderQos rqos = dds::DATAREADER_QOS_DEFAULT;
  rqos.reliability().kind = dds::BEST_EFFORT_RELIABILITY_QOS;
  rqos.history().kind = dds::KEEP_LAST_HISTORY_QOS;
  rqos.history().depth = 16;
  rqos.data_sharing().off();
  for (size_t i = 0; i < read_topics.size(); ++i) {
    auto* topic = participant_->create_topic(read_topics[i], type.get_type_name(), dds::TOPIC_QOS_DEFAULT);
    listeners_.push_back(std::make_unique<ReaderListener>(static_cast<int>(i), on_sample));
    auto* reader = topic != nullptr ? subscriber->create_datareader(topic, rqos, listeners_.back().get()) : nullptr;
    if (reader == nullptr) throw std::runtime_error("bare Fast DDS: no reader on " + read_topics[i]);
    readers_.push_back(reader);
  }
}

BareDds::~BareDds() {
  if (participant_ == nullptr) return;
  // the readers go before their listeners
  participant_->delete_contained_entities();
  dds::DomainParticipantFactory::get_instance()->delete_participant(participant_);
}

bool BareDds::write(int topic, msg::JointState& sample) { return writers_[static_cast<size_t>(topic)]->write(&sample); }

bool BareDds::all_matched() const {
  for (auto* w : writers_) {
    dds::PublicationMatchedStatus s;
    if (w->get_publication_matched_status(s) != ReturnCode_t::RETCODE_OK || s.current_count < 1) return false;
  }
  for (auto* r : readers_) {
    dds::SubscriptionMatchedStatus s;
    if (r->get_subscription_matched_status(s) != ReturnCode_t::RETCODE_OK || s.current_count < 1) return false;
  }
  return true;
}

}  // namespace teleop::bench
