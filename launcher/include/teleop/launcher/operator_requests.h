#pragma once
// An operator's requests to running nodes, sent on the bus from a short-lived tool participant:
// `teleop reset NODE` (msg::ResetRequest: clear the latched faults, the follower's reflexes, and
// follow the commands again) and the stop chain's `teleop estop` / `teleop enable`
// (msg::EmergencyStop, docs/stop_chain.md).

#include <cstdint>
#include <optional>
#include <string>

namespace teleop::launcher {

struct BusRequestOptions {
  /// The node addressed, by name; empty (estop, enable only): every node.
  std::string target;
  /// A node configuration whose transport section (domain, discovery, security) to use; empty:
  /// the defaults on `domain_id`.
  std::string config_path;
  std::optional<int> domain_id;
  /// How long to wait for the nodes' readers to match and acknowledge [s].
  double timeout_s = 5.0;
};
using ResetOptions = BusRequestOptions;

/// Sends the request and waits until every matched reader has acknowledged it; returns how many
/// readers did, 0 when none matched or they did not acknowledge within the timeout. Throws
/// ConfigError on a bad config. A stop or enable goes out at the first reader's match and again to
/// readers matched later, until every node of this release heard on the domain within 1.5 s has it.
int send_reset(const ResetOptions& options);
/// An emergency stop (`engaged`) or the enable that ends one, said to come from `origin`.
int send_emergency_stop(const BusRequestOptions& options, bool engaged, const std::string& origin);

}  // namespace teleop::launcher
