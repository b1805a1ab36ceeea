#include "teleop/tools/topic_graph.h"

#include <spdlog/fmt/fmt.h>

#include <algorithm>
#include <set>

namespace teleop::tools {
namespace {

EndpointView view_of(const transport::EndpointInfo& info,
                     const std::map<transport::ParticipantId, transport::ParticipantInfo>& participants) {
  EndpointView view{"?", "?", info};
  if (const auto it = participants.find(info.participant()); it != participants.end()) {
    view.node = it->second.name;
    view.host = it->second.host;
  }
  return view;
}

std::string qos_text(const transport::EndpointInfo& e) {
  std::string text = e.reliable ? "reliable" : "best effort";
  text += e.transient_local ? ", transient local" : ", volatile";
  if (e.deadline_ns > 0) text += fmt::format(", deadline {:g} ms", e.deadline_ns * 1e-6);
  if (e.lease_ns > 0) text += fmt::format(", liveliness lease {:g} ms", e.lease_ns * 1e-6);
  return text;
}

std::string nodes_of(const std::vector<EndpointView>& endpoints) {
  std::set<std::string> names;
  for (const auto& e : endpoints) names.insert(e.node);
  std::string text;
  for (const auto& n : names) text += (text.empty() ? "" : ",") + n;
  return text.empty() ? "-" : text;
}

}  // namespace

void TopicGraph::on_participant(const transport::ParticipantInfo& participant, bool present) {
  std::lock_guard lock(mutex_);
  if (present) {
    participants_[participant.id] = participant;
    return;
  }
  participants_.erase(participant.id);
  std::erase_if(endpoints_, [&](const auto& e) { return e.second.participant() == participant.id; });
}

void TopicGraph::on_endpoint(const transport::EndpointInfo& endpoint, bool present) {
  std::lock_guard lock(mutex_);
  if (present) {
    endpoints_[endpoint.guid.bytes] = endpoint;
  } else {
    endpoints_.erase(endpoint.guid.bytes);
  }
}

std::vector<TopicView> TopicGraph::topics(const transport::ParticipantId& self) const {
  std::lock_guard lock(mutex_);
  std::map<std::string, TopicView> topics;
  for (const auto& [guid, info] : endpoints_) {
    if (info.participant() == self) continue;
    TopicView& topic = topics[info.topic];
    topic.name = info.topic;
    if (std::find(topic.types.begin(), topic.types.end(), info.type) == topic.types.end())
      topic.types.push_back(info.type);
    (info.is_writer ? topic.writers : topic.readers).push_back(view_of(info, participants_));
  }
  std::vector<TopicView> sorted;
  for (auto& [name, topic] : topics) sorted.push_back(std::move(topic));
  return sorted;
}

std::vector<transport::ParticipantInfo> TopicGraph::participants() const {
  std::lock_guard lock(mutex_);
  std::vector<transport::ParticipantInfo> list;
  for (const auto& [id, p] : participants_) list.push_back(p);
  std::sort(list.begin(), list.end(), [](const auto& a, const auto& b) { return a.name < b.name; });
  return list;
}

std::string format_topic_list(const std::vector<TopicView>& topics, bool verbose) {
  std::string text;
  for (const TopicView& t : topics) {
    std::string types;
    for (const auto& type : t.types) types += (types.empty() ? "" : "|") + type;
    text += fmt::format("{:<36} {:<30} {} writer{}, {} reader{}", t.name, types, t.writers.size(),
                        t.writers.size() == 1 ? "" : "s", t.readers.size(), t.readers.size() == 1 ? "" : "s");
    if (verbose) text += fmt::format("  (from {} to {})", nodes_of(t.writers), nodes_of(t.readers));
    text += "\n";
  }
  return text;
}

std::string format_topic_info(const TopicView& topic) {
  std::string text = fmt::format("topic: {}\n", topic.name);
  for (const auto& type : topic.types) text += fmt::format("type: {}\n", type);
  const auto section = [&](const char* title, const std::vector<EndpointView>& endpoints) {
    text += fmt::format("{}: {}\n", title, endpoints.size());
    for (const EndpointView& e : endpoints) {
      text += fmt::format("  - node: {} (host {})\n    qos: {}\n", e.node, e.host, qos_text(e.info));
    }
  };
  section("writers", topic.writers);
  section("readers", topic.readers);
  return text;
}

}  // namespace teleop::tools
