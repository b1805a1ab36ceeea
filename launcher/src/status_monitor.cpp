#include "teleop/launcher/status_monitor.h"

#include "teleop/common/config.h"
#include "teleop/runtime/status_names.h"

namespace teleop::launcher {

StatusMonitor::StatusMonitor(int domain_id, LogLine log) : log_(std::move(log)) {
  transport::ParticipantConfig config;
  config.domain_id = domain_id;
  config.name = "teleop_launcher";
  participant_ = std::make_unique<transport::Participant>(config);
  reader_ = participant_->make_reader(transport::topics::kNodeStatus);
}

void StatusMonitor::poll() {
  while (reader_.take_next(sample_)) on_status(sample_);
}

void StatusMonitor::on_status(const msg::NodeStatus& status) {
  const std::string node = status.header().source().to_string();
  BusStatus next;
  next.state = runtime::state_name(status.state());
  for (uint32_t f : status.fault_codes()) next.faults.push_back(runtime::fault_name(f));
  BusStatus& last = nodes_[node];
  next.reports = last.reports + 1;
  if (next.state != last.state || next.faults != last.faults) {
    std::string line = node + ": " + (last.state.empty() ? "(new)" : last.state) + " -> " + next.state;
    if (!next.faults.empty()) {
      line += " [";
      for (size_t i = 0; i < next.faults.size(); ++i) line += (i ? ", " : "") + next.faults[i];
      line += "]";
    }
    log_(line);
  }
  last = next;
}

int scenario_domain(const std::string& first_node_config, std::optional<int> override_domain) {
  if (override_domain) return *override_domain;
  return static_cast<int>(ConfigNode::load_file(first_node_config).child("transport").get_int("domain_id", Range{0, 232}));
}

}  // namespace teleop::launcher
