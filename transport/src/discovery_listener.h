#pragma once
// The participant's listener to discovery: keeps the impairment's peer directory current (which
// locators belong to which node) and tells a DiscoveryObserver (tools) what appears and goes.

#include <fastdds/dds/domain/DomainParticipantListener.hpp>

#include <memory>

#include "teleop/transport/discovery_observer.h"
#include "teleop/transport/impairment/impairment_engine.h"

namespace teleop::transport {

class DiscoveryListener : public eprosima::fastdds::dds::DomainParticipantListener {
 public:
  /// Either may be null.
  DiscoveryListener(std::shared_ptr<impairment::ImpairmentEngine> engine, DiscoveryObserver* observer)
      : engine_(std::move(engine)), observer_(observer) {}

  void on_participant_discovery(eprosima::fastdds::dds::DomainParticipant*,
                                eprosima::fastrtps::rtps::ParticipantDiscoveryInfo&& info) override;
  void on_publisher_discovery(eprosima::fastdds::dds::DomainParticipant*,
                              eprosima::fastrtps::rtps::WriterDiscoveryInfo&& info) override;
  void on_subscriber_discovery(eprosima::fastdds::dds::DomainParticipant*,
                               eprosima::fastrtps::rtps::ReaderDiscoveryInfo&& info) override;

 private:
  std::shared_ptr<impairment::ImpairmentEngine> engine_;
  DiscoveryObserver* observer_;
};

/// The property a participant announces its host name in.
inline constexpr const char* kHostProperty = "teleop.host";

}  // namespace teleop::transport
