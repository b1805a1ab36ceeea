#pragma once
// Who is on the bus: every participant with its host, every topic with its type, writers and
// readers, as discovery reports them. What `teleop topic list|info` prints and `teleop record`
// subscribes to.

#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "teleop/transport/discovery_observer.h"

namespace teleop::tools {

/// One writer or reader of a topic, with the node it belongs to.
struct EndpointView {
  std::string node;  ///< the participant's name ("?" until its announcement arrived)
  std::string host;
  transport::EndpointInfo info;
};

struct TopicView {
  std::string name;
  /// The DDS type name; several when endpoints disagree (a misconfiguration worth seeing).
  std::vector<std::string> types;
  std::vector<EndpointView> writers;
  std::vector<EndpointView> readers;
};

class TopicGraph : public transport::DiscoveryObserver {
 public:
  void on_participant(const transport::ParticipantInfo& participant, bool present) override;
  void on_endpoint(const transport::EndpointInfo& endpoint, bool present) override;

  /// The topics now, sorted by name. Endpoints of the participant `self` (the tool's own) are left
  /// out. Any thread.
  std::vector<TopicView> topics(const transport::ParticipantId& self) const;
  /// The participants now, by name.
  std::vector<transport::ParticipantInfo> participants() const;

 private:
  mutable std::mutex mutex_;
  std::map<transport::ParticipantId, transport::ParticipantInfo> participants_;
  std::map<std::array<uint8_t, 16>, transport::EndpointInfo> endpoints_;
};

/// The text of `teleop topic list` (one topic a line: name, type, writers and readers counts;
/// with `verbose` the nodes too) and `teleop topic info` (one topic: each endpoint, node, host, QoS).
std::string format_topic_list(const std::vector<TopicView>& topics, bool verbose);
std::string format_topic_info(const TopicView& topic);

}  // namespace teleop::tools
