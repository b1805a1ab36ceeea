#pragma once
// Joins the nodes' reports into one picture of the run: per node its loop, per topic and
// direction what was sent and what arrived.

#include <string>
#include <vector>

#include <map>

#include "teleop/launcher/status_monitor.h"
#include "teleop/runtime/node_report.h"

namespace teleop::launcher {

/// One topic as it flowed from its publishing node to one subscribing node.
struct TopicFlow {
  std::string topic;
  std::string from;  ///< publishing node ("?" when no report lists it as published)
  std::string to;    ///< receiving node
  uint64_t sent = 0;
  runtime::ReceivedTopic received;
};

struct RunSummary {
  std::vector<runtime::NodeReport> nodes;
  std::vector<TopicFlow> flows;
  /// The last NodeStatus each node published on the bus, by node name.
  std::map<std::string, BusStatus> bus_status;
};

RunSummary summarize(std::vector<runtime::NodeReport> reports);

/// Human-readable tables.
std::string format_summary(const RunSummary& summary, const std::string& scenario_name);

}  // namespace teleop::launcher
