#pragma once
// A node's membership in the DDS domain: owns the participant, its publisher, subscriber,
// topics, writers, readers and their listeners.

#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/Topic.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>

#include <cstring>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "teleop/common/node_event.h"
#include "teleop/transport/discovery_observer.h"
#include "teleop/transport/impairment/impairment_engine.h"
#include "teleop/transport/participant_config.h"
#include "teleop/transport/qos_profiles.h"
#include "teleop/transport/raw_endpoint.h"
#include "teleop/transport/reader.h"
#include "teleop/transport/sample_types.h"
#include "teleop/transport/topics.h"
#include "teleop/transport/type_support.h"
#include "teleop/transport/writer.h"

namespace teleop::transport {

/// Receives every sample of a reader on a Fast DDS thread (callback mode).
using SampleCallback = std::function<void(const void* sample)>;

class DiscoveryBooster;
class DiscoveryListener;
class QosProfileLoader;

/// One of the participant's readers, as NodeStatus and the flow watch see it.
struct ReaderFlow {
  std::string topic;
  const EndpointStatus* status = nullptr;
};

class Participant {
 public:
  /// Creates the DDS participant with the QoS of its profiles (qos_profiles.h). Throws ConfigError
  /// for a bad profiles file, std::runtime_error when DDS refuses the configuration.
  /// `observer` (tools; may be null) hears of every participant and endpoint discovered.
  explicit Participant(const ParticipantConfig& config, DiscoveryObserver* observer = nullptr);
  ~Participant();
  Participant(const Participant&) = delete;
  Participant& operator=(const Participant&) = delete;

  /// A writer on `topic` with the topic's QoS preset. Setup time only.
  template <typename T>
  Writer<T> make_writer(const TopicSpec<T>& topic) {
    auto [writer, status] = create_writer(topic.name, register_type<T>(), topic.qos);
    return Writer<T>(writer, status);
  }

  /// A reader on `topic` for non-blocking `take_next` from the control loop. Setup time only.
  template <typename T>
  Reader<T> make_reader(const TopicSpec<T>& topic) {
    auto [reader, status] = create_reader(topic.name, register_type<T>(), topic.qos, nullptr, nullptr);
    return Reader<T>(reader, status);
  }

  /// A reader that calls `on_sample` on a Fast DDS thread for every sample received, with the
  /// DataWriter that wrote it. The callback must be thread-safe with respect to whatever it touches.
  template <typename T>
  Reader<T> make_reader(const TopicSpec<T>& topic, std::function<void(const T&, const WriterId&)> on_sample) {
    auto sample = std::make_shared<T>();
    auto take = [sample, cb = std::move(on_sample)](eprosima::fastdds::dds::DataReader* r) {
      eprosima::fastdds::dds::SampleInfo info;
      WriterId writer;
      while (r->take_next_sample(sample.get(), &info) == eprosima::fastrtps::types::ReturnCode_t::RETCODE_OK) {
        if (!info.valid_data) continue;
        std::memcpy(writer.bytes.data(), info.publication_handle.value, writer.bytes.size());
        cb(*sample, writer);
      }
    };
    auto [reader, status] = create_reader(topic.name, register_type<T>(), topic.qos, std::move(take), sample);
    return Reader<T>(reader, status);
  }

  /// The same without the writer.
  template <typename T>
  Reader<T> make_reader(const TopicSpec<T>& topic, std::function<void(const T&)> on_sample) {
    return make_reader(topic, std::function<void(const T&, const WriterId&)>(
                                  [cb = std::move(on_sample)](const T& s, const WriterId&) { cb(s); }));
  }

  /// Tools: a reader of `topic` that hands every sample over as its serialized bytes, on a Fast
  /// DDS thread. The participant must not also have a typed endpoint of the same type.
  void make_raw_reader(const std::string& topic, const SampleType& type, QosPreset qos, RawSampleCallback on_sample);
  /// Tools: a writer of serialized samples of `type` on `topic`.
  RawWriter make_raw_writer(const std::string& topic, const SampleType& type, QosPreset qos);

  /// Announces this participant's endpoints again for a while (ParticipantConfig::discovery_boost_ns),
  /// and from now on whenever another participant appears. A node calls it once all its endpoints
  /// exist; no endpoint may be created after (Fast DDS 2.9 asserts on one re-announced while being
  /// made). Participants that never call it (tools) never re-announce.
  void boost_discovery();

  /// Every reader created so far, in creation order. Setup time (allocates).
  std::vector<ReaderFlow> reader_flows() const;

  /// This participant's GUID prefix (what its own endpoints are known by in discovery).
  ParticipantId id() const;

  const ParticipantConfig& config() const { return config_; }
  /// The QoS its writers and readers get, per preset: profiles plus the YAML's overrides.
  const EndpointQos& endpoint_qos() const { return endpoint_qos_; }
  /// Where the QoS profiles came from: a path and what chose it (for a node's log).
  const std::string& qos_profiles_source() const { return qos_profiles_source_; }
  /// The impairment of outgoing traffic; null when none is configured.
  const impairment::ImpairmentEngine* impairment() const { return impairment_.get(); }
  eprosima::fastdds::dds::DomainParticipant* dds() { return participant_; }
  /// What the node's loop saw happen (writers followed and refused, state changes), on its way
  /// to the node's log. The loop's thread produces, the node's event log consumes.
  NodeEventQueue& events() { return *events_; }

 private:
  struct WriterListener;
  struct ReaderListener;
  using TakeFunction = std::function<void(eprosima::fastdds::dds::DataReader*)>;

  // registers T under its DDS name of the configured naming; returns that name
  template <typename T>
  std::string register_type() {
    eprosima::fastdds::dds::TypeSupport type(new typename PubSubTypeOf<T>::type());
    return register_type_support(type);
  }
  std::string register_type_support(eprosima::fastdds::dds::TypeSupport type);
  // the publisher, the subscriber and the endpoint QoS, once the participant exists
  void create_entities(const eprosima::fastdds::dds::DomainParticipantQos& qos, const QosProfileLoader& profiles);
  eprosima::fastdds::dds::Topic* topic_for(const std::string& name, const std::string& type_name);
  std::pair<eprosima::fastdds::dds::DataWriter*, const EndpointStatus*> create_writer(const std::string& topic,
                                                                                      const std::string& type_name,
                                                                                      QosPreset preset);
  std::pair<eprosima::fastdds::dds::DataReader*, EndpointStatus*> create_reader(
      const std::string& topic, const std::string& type_name, QosPreset preset, TakeFunction take,
      std::shared_ptr<void> keep_alive);

  ParticipantConfig config_;
  std::unique_ptr<NodeEventQueue> events_ = std::make_unique<NodeEventQueue>();
  EndpointQos endpoint_qos_;
  std::string qos_profiles_source_;
  std::shared_ptr<impairment::ImpairmentEngine> impairment_;
  std::unique_ptr<DiscoveryListener> discovery_listener_;
  std::unique_ptr<DiscoveryBooster> discovery_booster_;
  eprosima::fastdds::dds::DomainParticipant* participant_ = nullptr;
  eprosima::fastdds::dds::Publisher* publisher_ = nullptr;
  eprosima::fastdds::dds::Subscriber* subscriber_ = nullptr;
  std::map<std::string, eprosima::fastdds::dds::Topic*> topics_;
  std::vector<std::unique_ptr<WriterListener>> writer_listeners_;
  std::vector<std::unique_ptr<ReaderListener>> reader_listeners_;
};

}  // namespace teleop::transport
