#include "discovery_listener.h"

#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastrtps/utils/IPLocator.h>

#include <spdlog/spdlog.h>

#include <cstring>
#include <optional>
#include <sstream>
#include <vector>

namespace teleop::transport {
namespace {

using eprosima::fastrtps::rtps::GUID_t;
using eprosima::fastrtps::rtps::IPLocator;
using eprosima::fastrtps::rtps::Locator_t;
using eprosima::fastrtps::rtps::ParticipantAuthenticationInfo;
using eprosima::fastrtps::rtps::ParticipantDiscoveryInfo;
using eprosima::fastrtps::rtps::ParticipantProxyData;
using eprosima::fastrtps::rtps::ReaderDiscoveryInfo;
using eprosima::fastrtps::rtps::WriterDiscoveryInfo;

WriterId id_of(const GUID_t& guid) {
  WriterId id;
  std::memcpy(id.bytes.data(), guid.guidPrefix.value, 12);
  std::memcpy(id.bytes.data() + 12, guid.entityId.value, 4);
  return id;
}

int64_t to_ns(const eprosima::fastrtps::Duration_t& d) {
  if (d == eprosima::fastrtps::c_TimeInfinite) return 0;
  return static_cast<int64_t>(d.seconds) * 1'000'000'000 + static_cast<int64_t>(d.nanosec);
}

std::string host_of(const ParticipantProxyData& data) {
  for (const auto& property : data.m_properties) {
    if (property.first() == kHostProperty) return property.second();
  }
  for (const auto& locator : data.default_locators.unicast) return IPLocator::ip_to_string(locator);
  return "?";
}

template <typename Qos>
void fill_qos(const Qos& qos, EndpointInfo& info) {
  info.reliable = qos.m_reliability.kind == eprosima::fastdds::dds::RELIABLE_RELIABILITY_QOS;
  info.transient_local = qos.m_durability.kind != eprosima::fastdds::dds::VOLATILE_DURABILITY_QOS;
  info.deadline_ns = to_ns(qos.m_deadline.period);
  info.lease_ns = to_ns(qos.m_liveliness.lease_duration);
}

// nullopt for an endpoint whose topic is not one of `naming`'s
template <typename ProxyData>
std::optional<EndpointInfo> endpoint_of(const ProxyData& data, bool is_writer, Naming naming) {
  auto topic = teleop_topic_name(naming, data.topicName().to_string());
  if (!topic) return std::nullopt;
  EndpointInfo info;
  info.guid = id_of(data.guid());
  info.is_writer = is_writer;
  info.topic = std::move(*topic);
  info.type = data.typeName().to_string();
  fill_qos(data.m_qos, info);
  return info;
}

}  // namespace

void DiscoveryListener::on_participant_discovery(eprosima::fastdds::dds::DomainParticipant* p,
                                                 ParticipantDiscoveryInfo&& info) {
  const std::string name = info.info.m_participantName.to_string();
  const bool gone = info.status == ParticipantDiscoveryInfo::REMOVED_PARTICIPANT ||
                    info.status == ParticipantDiscoveryInfo::DROPPED_PARTICIPANT;
  if (engine_) {
    if (gone) {
      engine_->peers().remove(name);
    } else {
      std::vector<Locator_t> locators;
      for (const auto& l : info.info.default_locators.unicast) locators.push_back(l);
      for (const auto& l : info.info.default_locators.multicast) locators.push_back(l);
      for (const auto& l : info.info.metatraffic_locators.unicast) locators.push_back(l);
      engine_->peers().add(name, locators);
    }
  }
  if (info.status == ParticipantDiscoveryInfo::DISCOVERED_PARTICIPANT) {
    const std::lock_guard lock(new_participant_mutex_);
    if (new_participant_) new_participant_();
  }
  if (!gone && !own_name_.empty() && name == own_name_ && p != nullptr && info.info.m_guid.guidPrefix != p->guid().guidPrefix &&
      info.status == ParticipantDiscoveryInfo::DISCOVERED_PARTICIPANT) {
    spdlog::warn("{}: another participant named '{}' joined domain {} from host {}: nodes of one name mix their "
                 "samples and cannot be told apart by name; give each node a node.name of its own",
                 own_name_, name, p->get_domain_id(), host_of(info.info));
  }
  if (observer_) {
    ParticipantInfo participant;
    std::memcpy(participant.id.data(), info.info.m_guid.guidPrefix.value, participant.id.size());
    participant.name = name;
    participant.host = host_of(info.info);
    observer_->on_participant(participant, !gone);
  }
}

void DiscoveryListener::on_publisher_discovery(eprosima::fastdds::dds::DomainParticipant*, WriterDiscoveryInfo&& info) {
  if (!observer_) return;
  const bool gone = info.status == WriterDiscoveryInfo::REMOVED_WRITER;
  if (auto endpoint = endpoint_of(info.info, true, naming_)) observer_->on_endpoint(*endpoint, !gone);
}

void DiscoveryListener::on_subscriber_discovery(eprosima::fastdds::dds::DomainParticipant*,
                                                ReaderDiscoveryInfo&& info) {
  if (!observer_) return;
  const bool gone = info.status == ReaderDiscoveryInfo::REMOVED_READER;
  if (auto endpoint = endpoint_of(info.info, false, naming_)) observer_->on_endpoint(*endpoint, !gone);
}

#if HAVE_SECURITY
void DiscoveryListener::onParticipantAuthentication(eprosima::fastdds::dds::DomainParticipant* participant,
                                                    ParticipantAuthenticationInfo&& info) {
  if (info.status != ParticipantAuthenticationInfo::UNAUTHORIZED_PARTICIPANT) return;
  std::ostringstream guid;
  guid << info.guid;
  spdlog::warn("{}: refused the security handshake of participant {} in domain {}: its identity did not verify "
               "against our identity CA or its permissions do not let it join (Fast DDS's security errors above "
               "name the check that failed)",
               own_name_.empty() ? "participant" : own_name_, guid.str(), participant->get_domain_id());
}
#endif

}  // namespace teleop::transport
