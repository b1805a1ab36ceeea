#pragma once
// What every bus tool starts with: a participant on the nodes' domain that listens to discovery.

#include <memory>
#include <optional>
#include <string>

#include "teleop/tools/topic_graph.h"
#include "teleop/tools/topic_tools.h"
#include "teleop/transport/participant.h"
#include "teleop/transport/sample_types.h"

namespace teleop::tools {

class Bus {
 public:
  /// Joins the domain as participant `name`. Throws ConfigError on a bad node config.
  Bus(const BusOptions& options, const std::string& name);

  /// Waits up to the discovery time for `topic` to have a writer; nullopt when it has none then
  /// (or the user interrupted).
  std::optional<TopicView> wait_for_writers(const std::string& topic) const;
  /// The teleop type of a discovered topic. Throws std::runtime_error naming the topic when its
  /// writers disagree or the type is not a teleop type.
  static const transport::SampleType& type_of(const TopicView& topic);
  /// Sleeps the discovery time (interruptible), so that list and info see everyone.
  void listen() const;

  std::vector<TopicView> topics() const { return graph_.topics(participant_->id()); }
  transport::Participant& participant() { return *participant_; }
  int domain_id() const { return participant_->config().domain_id; }
  const BusOptions& options() const { return options_; }

 private:
  BusOptions options_;
  TopicGraph graph_;  // before the participant: it is told of discovery until the participant goes
  std::unique_ptr<transport::Participant> participant_;
};

/// The error for a topic nobody writes.
std::string no_writer_message(const std::string& topic, const Bus& bus);

}  // namespace teleop::tools
