#include "teleop/transport/participant.h"

#include <fastdds/rtps/attributes/ServerAttributes.h>
#include <fastdds/rtps/transport/UDPv4TransportDescriptor.h>
#include <fastdds/rtps/transport/shared_mem/SharedMemTransportDescriptor.h>
#include <fastrtps/utils/IPLocator.h>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/domain/DomainParticipantListener.hpp>
#include <fastdds/dds/domain/qos/DomainParticipantQos.hpp>
#include <fastdds/dds/publisher/DataWriterListener.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>

#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include <spdlog/spdlog.h>

#include "teleop/common/clock.h"
#include "discovery_booster.h"
#include "discovery_listener.h"
#include "impairment/impairing_transport.h"
#include "qos_profile_loader.h"
#include "raw_payload_type.h"
#include "teleop/transport/qos.h"
#include "security_files.h"

namespace teleop::transport {
namespace dds = eprosima::fastdds::dds;
using eprosima::fastrtps::rtps::IPLocator;
using eprosima::fastrtps::rtps::Locator_t;

struct Participant::WriterListener : dds::DataWriterListener {
  EndpointStatus status;
  void on_publication_matched(dds::DataWriter*, const dds::PublicationMatchedStatus& s) override {
    status.matched.store(s.current_count, std::memory_order_relaxed);
  }
  void on_offered_deadline_missed(dds::DataWriter*, const dds::OfferedDeadlineMissedStatus&) override {
    status.deadline_missed.fetch_add(1, std::memory_order_relaxed);
  }
};

struct Participant::ReaderListener : dds::DataReaderListener {
  std::string topic;
  EndpointStatus status;
  TakeFunction take;               // set in callback mode only
  std::shared_ptr<void> keep_alive;  // the sample buffer the callback takes into
  void on_data_available(dds::DataReader* reader) override {
    const int64_t now = monotonic_now_ns();
    status.last_data_mono_ns.store(now, std::memory_order_relaxed);
    if (status.freshness.enabled()) status.freshness.on_arrival(now);
    if (take) take(reader);
  }
  void on_subscription_matched(dds::DataReader*, const dds::SubscriptionMatchedStatus& s) override {
    status.matched.store(s.current_count, std::memory_order_relaxed);
    if (s.current_count == 0 && status.freshness.enabled()) status.freshness.on_unmatched(monotonic_now_ns());
  }
  void on_liveliness_changed(dds::DataReader*, const dds::LivelinessChangedStatus& s) override {
    // Fast DDS 2.9 can report a writer's lapse without having reported it alive (seen under CPU load: alive_count -1)
    status.alive.store(std::max(s.alive_count, 0), std::memory_order_relaxed);
    if (s.not_alive_count_change > 0) {
      status.liveliness_lost.fetch_add(static_cast<uint64_t>(s.not_alive_count_change), std::memory_order_relaxed);
    }
  }
  void on_requested_deadline_missed(dds::DataReader*, const dds::RequestedDeadlineMissedStatus&) override {
    status.deadline_missed.fetch_add(1, std::memory_order_relaxed);
  }
};

// tells the impairment where each peer listens, so a destination maps to its link
namespace {

Locator_t peer_locator(const std::string& peer) {
  Locator_t loc;
  const auto colon = peer.rfind(':');
  IPLocator::setIPv4(loc, peer.substr(0, colon));
  // port 0: Fast DDS fills in the domain's well-known discovery ports for the first participants
  loc.port = colon == std::string::npos ? 0 : static_cast<uint32_t>(std::stoul(peer.substr(colon + 1)));
  return loc;
}

// a client of each server; the servers' GUID prefixes follow from their ids (`fastdds discovery -i`)
void add_discovery_servers(const std::vector<DiscoveryServer>& servers, dds::DomainParticipantQos& qos) {
  auto& discovery = qos.wire_protocol().builtin.discovery_config;
  discovery.discoveryProtocol = eprosima::fastrtps::rtps::DiscoveryProtocol_t::CLIENT;
  for (const auto& server : servers) {
    eprosima::fastdds::rtps::RemoteServerAttributes remote;
    if (!eprosima::fastdds::rtps::get_server_client_default_guidPrefix(server.id, remote.guidPrefix)) {
      throw std::runtime_error("no discovery server GUID prefix for id " + std::to_string(server.id));
    }
    Locator_t locator;
    IPLocator::setIPv4(locator, server.address);
    locator.port = server.port;
    remote.metatrafficUnicastLocatorList.push_back(locator);
    discovery.m_DiscoveryServers.push_back(remote);
  }
}

// DDS Security by the builtin plugins: PKI-DH authentication, permissions, AES-GCM-GMAC
void add_security(const SecurityConfig& security, dds::DomainParticipantQos& qos) {
  auto& properties = qos.properties().properties();
  // Fast DDS takes file:// URIs only
  const auto file = [](const std::string& path) { return "file://" + std::filesystem::absolute(path).string(); };
  properties.emplace_back("dds.sec.auth.plugin", "builtin.PKI-DH");
  properties.emplace_back("dds.sec.auth.builtin.PKI-DH.identity_ca", file(security.identity_ca));
  properties.emplace_back("dds.sec.auth.builtin.PKI-DH.identity_certificate", file(security.identity_certificate));
  properties.emplace_back("dds.sec.auth.builtin.PKI-DH.private_key", file(security.private_key));
  properties.emplace_back("dds.sec.access.plugin", "builtin.Access-Permissions");
  properties.emplace_back("dds.sec.access.builtin.Access-Permissions.permissions_ca", file(security.permissions_ca));
  properties.emplace_back("dds.sec.access.builtin.Access-Permissions.governance", file(security.governance));
  properties.emplace_back("dds.sec.access.builtin.Access-Permissions.permissions", file(security.permissions));
  properties.emplace_back("dds.sec.crypto.plugin", "builtin.AES-GCM-GMAC");
}

// The participant profile (qos_profile_loader.h) with what the node's YAML decides: name,
// transports, discovery and security replace whatever the profile says about them.
dds::DomainParticipantQos participant_qos(dds::DomainParticipantQos qos, const ParticipantConfig& config,
                                          const std::shared_ptr<impairment::ImpairmentEngine>& engine) {
  qos.name(config.name);
  // the tools show which host each node runs on
  char host[256] = {};
  if (gethostname(host, sizeof(host) - 1) == 0) qos.properties().properties().emplace_back(kHostProperty, host, true);
  qos.transport().use_builtin_transports = false;
  qos.transport().user_transports.clear();
  // impaired traffic must all go through the chaining transport: shared memory would bypass it
  if (config.shm && !engine) {
    qos.transport().user_transports.push_back(std::make_shared<eprosima::fastdds::rtps::SharedMemTransportDescriptor>());
  }
  if (config.udpv4) {
    auto udp = std::make_shared<eprosima::fastdds::rtps::UDPv4TransportDescriptor>();
    // a send that cannot go out (link down, full socket buffer) must drop the datagram, not block
    // the control loop that publishes: measured, a cut link stalled the loop for the whole
    // participant lease with blocking sends
    udp->non_blocking_send = true;
    for (const auto& itf : config.interface_whitelist) udp->interfaceWhiteList.push_back(itf);
    // Fast DDS reaches an address of this host (a discovery server or a peer on it) through
    // loopback: a whitelist without it made a server on the same host unreachable (found in
    // test/netns). Loopback never leaves the host, so the whitelist still picks the networks.
    const auto& whitelist = config.interface_whitelist;
    if (!whitelist.empty() && std::find(whitelist.begin(), whitelist.end(), "127.0.0.1") == whitelist.end()) {
      udp->interfaceWhiteList.push_back("127.0.0.1");
    }
    if (engine) {
      qos.transport().user_transports.push_back(std::make_shared<impairment::ImpairingTransportDescriptor>(udp, engine));
    } else {
      qos.transport().user_transports.push_back(udp);
    }
  }
  qos.wire_protocol().builtin.initialPeersList.clear();
  for (const auto& peer : config.initial_peers) {
    qos.wire_protocol().builtin.initialPeersList.push_back(peer_locator(peer));
  }
  auto& discovery = qos.wire_protocol().builtin.discovery_config;
  discovery.discoveryProtocol = eprosima::fastrtps::rtps::DiscoveryProtocol_t::SIMPLE;
  discovery.m_DiscoveryServers.clear();
  if (config.discovery == DiscoveryMode::kServer) add_discovery_servers(config.discovery_servers, qos);
  // security is the YAML's alone: a profile's dds.sec.* properties would mix with its files
  auto& properties = qos.properties().properties();
  std::erase_if(properties, [](const auto& p) { return p.name().starts_with("dds.sec."); });
  if (config.security.enabled()) add_security(config.security, qos);
  return qos;
}

}  // namespace

Participant::Participant(const ParticipantConfig& config, DiscoveryObserver* observer) : config_(config) {
  dds::StatusMask mask = dds::StatusMask::none();
  if (config.impairment.enabled()) {
    if (!config.udpv4) throw std::runtime_error("network impairment needs the udpv4 transport");
    impairment_ = std::make_shared<impairment::ImpairmentEngine>(config.impairment, config.name);
    spdlog::info("{}: impairing outgoing traffic (seed {}{}), shared memory off so nothing bypasses it", config.name,
                 config.impairment.seed, config.impairment.exclude_discovery ? ", discovery unimpaired" : "");
    for (const auto& l : config.impairment.links) spdlog::info("{}: link to {}: profile {}", config.name, l.to, l.profile.name);
  }
  discovery_listener_ = std::make_unique<DiscoveryListener>(impairment_, observer, config.naming,
                                                            config.warn_same_name ? config.name : std::string());
  if (config.security.enabled()) verify_security_files(config.security);
  register_type_objects();
  const QosProfileLoader profiles(config);
  qos_profiles_source_ = profiles.source();
  const dds::DomainParticipantQos qos = participant_qos(profiles.participant_qos(), config, impairment_);
  auto* factory = dds::DomainParticipantFactory::get_instance();
  participant_ = factory->create_participant(static_cast<dds::DomainId_t>(config.domain_id), qos,
                                             discovery_listener_.get(), mask);
  if (participant_ == nullptr) {
    throw std::runtime_error(
        "DDS refused to create participant '" + config.name + "' in domain " + std::to_string(config.domain_id) +
        (config.security.enabled() ? " (security on: see the Fast DDS security errors above)" : ""));
  }
  try {
    create_entities(qos, profiles);
  } catch (...) {
    // no destructor runs for a half-built object: the participant would outlive it
    participant_->delete_contained_entities();
    factory->delete_participant(participant_);
    throw;
  }
}

void Participant::create_entities(const dds::DomainParticipantQos& qos, const QosProfileLoader& profiles) {
  publisher_ = participant_->create_publisher(dds::PUBLISHER_QOS_DEFAULT);
  subscriber_ = participant_->create_subscriber(dds::SUBSCRIBER_QOS_DEFAULT);
  if (publisher_ == nullptr || subscriber_ == nullptr) {
    throw std::runtime_error("DDS refused to create the publisher/subscriber of '" + config_.name + "'");
  }
  endpoint_qos_ = profiles.endpoint_qos(*publisher_, *subscriber_, qos);
  discovery_booster_ = std::make_unique<DiscoveryBooster>(
      *publisher_, *subscriber_, DiscoveryBoost{config_.discovery_boost_ns, config_.discovery_boost_period_ns});
  discovery_listener_->on_new_participant([booster = discovery_booster_.get()] { booster->kick(); });
}

Participant::~Participant() {
  // nothing re-announces the endpoints while they are deleted, and no discovery kicks the booster
  // once it is gone (the listener lives on with the participant)
  discovery_listener_->on_new_participant(nullptr);
  discovery_booster_.reset();
  // the delay line sends through resources the participant owns: stop it first
  if (impairment_) impairment_->shutdown();
  if (participant_ == nullptr) return;
  // entities go before their listeners, the participant last
  participant_->delete_contained_entities();
  dds::DomainParticipantFactory::get_instance()->delete_participant(participant_);
}

std::string Participant::register_type_support(dds::TypeSupport type) {
  // renamed before registering, so that the type's own name and the announced one agree
  const std::string name = dds_type_name(config_.naming, type.get_type_name());
  if (name != type.get_type_name()) type->setName(name.c_str());
  // Discovery announces neither the type objects nor the type information (docs/transport.md,
  // "Type objects"). Fast DDS 2.9 builds a dynamic type from an announced type object of a type it
  // does not know and crashes on a sequence of a struct (eProsima/Fast-DDS#2184): the discovery
  // server did, at our first writer. And it writes the type information (PID 0x75) as an
  // encapsulation header and plain CDR, not as XTypes 1.3's XCDR2: Cyclone DDS 0.10 (rmw_cyclonedds)
  // rejects it and drops the endpoint, so no Cyclone reader or writer would ever match ours.
  type->auto_fill_type_object(false);
  type->auto_fill_type_information(false);
  if (participant_->find_type(name).empty()) {
    if (type.register_type(participant_) != eprosima::fastrtps::types::ReturnCode_t::RETCODE_OK) {
      throw std::runtime_error("DDS refused to register type " + name);
    }
  }
  return name;
}

dds::Topic* Participant::topic_for(const std::string& name, const std::string& type_name) {
  auto it = topics_.find(name);
  if (it != topics_.end()) return it->second;
  dds::Topic* topic =
      participant_->create_topic(dds_topic_name(config_.naming, name), type_name, dds::TOPIC_QOS_DEFAULT);
  if (topic == nullptr) throw std::runtime_error("DDS refused to create topic " + name);
  topics_.emplace(name, topic);
  return topic;
}

std::pair<dds::DataWriter*, const EndpointStatus*> Participant::create_writer(const std::string& topic,
                                                                              const std::string& type_name,
                                                                              QosPreset preset) {
  auto listener = std::make_unique<WriterListener>();
  // streams: no DDS deadline or liveliness, their readers check both (stream_freshness.h)
  dds::DataWriter* writer = publisher_->create_datawriter(
      topic_for(topic, type_name),
      preset == QosPreset::kStream ? without_dds_timers(endpoint_qos_.writer(preset)) : endpoint_qos_.writer(preset),
      listener.get());
  if (writer == nullptr) throw std::runtime_error("DDS refused to create a writer on " + topic);
  const EndpointStatus* status = &listener->status;
  writer_listeners_.push_back(std::move(listener));
  return {writer, status};
}

std::pair<dds::DataReader*, EndpointStatus*> Participant::create_reader(const std::string& topic,
                                                                        const std::string& type_name, QosPreset preset,
                                                                        TakeFunction take,
                                                                        std::shared_ptr<void> keep_alive) {
  auto listener = std::make_unique<ReaderListener>();
  listener->topic = topic;
  listener->take = std::move(take);
  listener->keep_alive = std::move(keep_alive);
  // streams: deadline and liveliness from arrivals, not DDS timers (stream_freshness.h)
  const bool stream = preset == QosPreset::kStream;
  if (stream) {
    const StreamChecks checks = stream_checks(endpoint_qos_.reader(preset));
    listener->status.freshness.configure(checks.lease_ns, checks.deadline_ns);
  }
  dds::DataReader* reader = subscriber_->create_datareader(
      topic_for(topic, type_name),
      stream ? without_dds_timers(endpoint_qos_.reader(preset)) : endpoint_qos_.reader(preset), listener.get());
  if (reader == nullptr) throw std::runtime_error("DDS refused to create a reader on " + topic);
  EndpointStatus* status = &listener->status;
  reader_listeners_.push_back(std::move(listener));
  return {reader, status};
}

void Participant::make_raw_reader(const std::string& topic, const SampleType& type, QosPreset qos,
                                  RawSampleCallback on_sample) {
  auto sample = std::make_shared<RawSample>();
  auto take = [sample, cb = std::move(on_sample)](dds::DataReader* r) {
    dds::SampleInfo info;
    while (r->take_next_sample(&sample->cdr, &info) == eprosima::fastrtps::types::ReturnCode_t::RETCODE_OK) {
      if (!info.valid_data) continue;
      sample->reception_ns = info.reception_timestamp.to_ns();
      std::memcpy(sample->writer.bytes.data(), info.publication_handle.value, sample->writer.bytes.size());
      cb(*sample);
    }
  };
  (void)create_reader(topic, register_type_support(dds::TypeSupport(new RawPayloadType(type))), qos, std::move(take),
                      sample);
}

RawWriter Participant::make_raw_writer(const std::string& topic, const SampleType& type, QosPreset qos) {
  auto [writer, status] = create_writer(topic, register_type_support(dds::TypeSupport(new RawPayloadType(type))), qos);
  return RawWriter(writer, status);
}

ParticipantId Participant::id() const {
  ParticipantId id{};
  std::memcpy(id.data(), participant_->guid().guidPrefix.value, id.size());
  return id;
}

void Participant::boost_discovery() { discovery_booster_->arm_and_kick(); }

std::vector<ReaderFlow> Participant::reader_flows() const {
  std::vector<ReaderFlow> flows;
  for (const auto& listener : reader_listeners_) flows.push_back({listener->topic, &listener->status});
  return flows;
}

}  // namespace teleop::transport
