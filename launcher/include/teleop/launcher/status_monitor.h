#pragma once
// Watches NodeStatus on the bus: logs every node's state transitions and faults as they are
// reported, and keeps the last status of each node for the summary.

#include <functional>
#include <optional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <teleop/msg/status.h>

#include "teleop/transport/participant.h"

namespace teleop::launcher {

/// The last status a node reported on the bus.
struct BusStatus {
  std::string state;
  std::vector<std::string> faults;
  uint64_t reports = 0;
};

class StatusMonitor {
 public:
  using LogLine = std::function<void(const std::string&)>;

  /// Joins `domain_id` (UDP) and subscribes to NodeStatus.
  StatusMonitor(int domain_id, LogLine log);

  /// Takes what arrived; logs changes of state or faults. Non-blocking.
  void poll();

  const std::map<std::string, BusStatus>& nodes() const { return nodes_; }

 private:
  void on_status(const msg::NodeStatus& status);

  LogLine log_;
  std::unique_ptr<transport::Participant> participant_;
  transport::Reader<msg::NodeStatus> reader_;
  msg::NodeStatus sample_;
  std::map<std::string, BusStatus> nodes_;
};

/// The DDS domain the nodes of a scenario use: the override, else the first node config's
/// transport.domain_id.
int scenario_domain(const std::string& first_node_config, std::optional<int> override_domain);

}  // namespace teleop::launcher
