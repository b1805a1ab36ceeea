#pragma once
// Publishes NodeStatus at a low rate from inside the control loop.

#include <cstdint>
#include <string>
#include <vector>

#include "teleop/common/rate_pacer.h"
#include "teleop/runtime/node_logic.h"
#include "teleop/transport/publication.h"

namespace teleop::runtime {

class StatusPublisher {
 public:
  /// `architecture`: the teleoperation architecture the node plays, said in every status (empty: none).
  StatusPublisher(transport::Participant& participant, const std::string& node_name, msg::NodeRole role,
                  const std::string& architecture, double loop_rate_hz, double status_rate_hz);

  /// Publishes when a status period has passed since the last one, or at once when the node's
  /// state or faults `changed` (a leader waits for its follower's word that it follows it).
  /// Real-time safe.
  void maybe_publish(const CycleTick& tick, const NodeLogic& logic, const PacerStats& loop, bool changed = false);
  /// Publishes now with the given state.
  void publish(msg::NodeState state, const NodeLogic& logic, const PacerStats& loop);
  /// Publishes STATE_STOPPING and waits (at most `timeout_ns`) until the status readers have it,
  /// so that the bus learns the node stopped rather than seeing it vanish. Shutdown only.
  void publish_stopping(const NodeLogic& logic, const PacerStats& loop, int64_t timeout_ns);

 private:
  void init_flows(const transport::Participant& participant);
  void fill_links();
  void fill_flows();
  static void fill_authority(const transport::FlowAuthority& a, msg::FlowStatus& f);

  const transport::impairment::ImpairmentEngine* impairment_;
  std::vector<transport::impairment::ImpairmentEngine::Snapshot> links_;
  transport::Publication<msg::NodeStatus> publication_;
  std::vector<uint32_t> faults_;
  std::vector<const transport::EndpointStatus*> flows_;
  uint64_t cycles_per_status_;
};

}  // namespace teleop::runtime
