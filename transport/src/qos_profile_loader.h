#pragma once
// Reads the QoS profiles of one participant being created through Fast DDS's profile registry
// (DomainParticipantFactory::load_XML_profiles_*, get_*_qos_from_profile). That registry is one
// per process and refuses a second profile of a name it holds, so a loader has it to itself for
// its lifetime: it empties it, loads the one file its participant uses, and empties it again when
// done (participants of one process may use different files; the tests do).

#include <fastdds/dds/domain/qos/DomainParticipantQos.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>

#include <mutex>
#include <string>

#include "teleop/transport/participant_config.h"
#include "teleop/transport/qos_profiles.h"

namespace teleop::transport {

class QosProfileLoader {
 public:
  /// Loads the profiles file `config` leads to (qos_profiles.h). Throws ConfigError naming the
  /// file (and line) when it is missing or malformed, and the profile when one is not defined.
  explicit QosProfileLoader(const ParticipantConfig& config);
  ~QosProfileLoader();
  QosProfileLoader(const QosProfileLoader&) = delete;
  QosProfileLoader& operator=(const QosProfileLoader&) = delete;

  /// Where the profiles come from, for logs: the path and what chose it.
  const std::string& source() const { return source_; }

  /// The participant profile with the node's YAML overrides.
  eprosima::fastdds::dds::DomainParticipantQos participant_qos() const;

  /// Every preset's writer and reader profile with the node's YAML overrides. Fast DDS 2.9 reads
  /// endpoint profiles through a publisher and a subscriber, so the participant exists by now.
  /// Throws ConfigError when a writer's liveliness lease is longer than `participant`'s lease.
  EndpointQos endpoint_qos(eprosima::fastdds::dds::Publisher& publisher, eprosima::fastdds::dds::Subscriber& subscriber,
                           const eprosima::fastdds::dds::DomainParticipantQos& participant) const;

 private:
  void load(const std::string& file);
  void load_builtin();
  ConfigError error(const std::string& key, const std::string& problem) const;

  std::unique_lock<std::mutex> registry_lock_;
  const ParticipantConfig& config_;
  std::string file_;    // what errors name
  std::string source_;  // file_ and what chose it
};

}  // namespace teleop::transport
