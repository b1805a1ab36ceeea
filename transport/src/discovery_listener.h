#pragma once
// The participant's listener to discovery: keeps the impairment's peer directory current (which
// locators belong to which node) and tells a DiscoveryObserver (tools) what appears and goes.

#include <fastdds/dds/domain/DomainParticipantListener.hpp>

#include <functional>
#include <memory>
#include <mutex>

#include "teleop/transport/discovery_observer.h"
#include "teleop/transport/impairment/impairment_engine.h"
#include "teleop/transport/naming.h"

namespace teleop::transport {

class DiscoveryListener : public eprosima::fastdds::dds::DomainParticipantListener {
 public:
  /// Either may be null. The observer hears of topics by their teleop names under `naming`
  /// (naming.h): a tool works with the same names on a plain and a ros2-named domain.
  /// `own_name`: warn when another participant of this name appears (empty: no check).
  DiscoveryListener(std::shared_ptr<impairment::ImpairmentEngine> engine, DiscoveryObserver* observer,
                    Naming naming, std::string own_name = {})
      : engine_(std::move(engine)), observer_(observer), naming_(naming), own_name_(std::move(own_name)) {}

  void on_participant_discovery(eprosima::fastdds::dds::DomainParticipant*,
                                eprosima::fastrtps::rtps::ParticipantDiscoveryInfo&& info) override;
  /// Called (on Fast DDS's thread) whenever another participant appears. Set to nullptr before
  /// what the callback touches goes: it returns once no call runs, and none comes after.
  void on_new_participant(std::function<void()> callback) {
    const std::lock_guard lock(new_participant_mutex_);
    new_participant_ = std::move(callback);
  }
  void on_publisher_discovery(eprosima::fastdds::dds::DomainParticipant*,
                              eprosima::fastrtps::rtps::WriterDiscoveryInfo&& info) override;
  void on_subscriber_discovery(eprosima::fastdds::dds::DomainParticipant*,
                               eprosima::fastrtps::rtps::ReaderDiscoveryInfo&& info) override;
#if HAVE_SECURITY
  /// A refused handshake is logged when it happens, with the participant it came from.
  void onParticipantAuthentication(eprosima::fastdds::dds::DomainParticipant* participant,
                                   eprosima::fastrtps::rtps::ParticipantAuthenticationInfo&& info) override;
#endif

 private:
  std::shared_ptr<impairment::ImpairmentEngine> engine_;
  DiscoveryObserver* observer_;
  Naming naming_;
  std::string own_name_;
  std::function<void()> new_participant_;
  // held while the callback runs: ASan saw a discovery kick the booster the participant had
  // just destroyed
  std::mutex new_participant_mutex_;
};

/// The property a participant announces its host name in.
inline constexpr const char* kHostProperty = "teleop.host";

}  // namespace teleop::transport
