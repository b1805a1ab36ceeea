#pragma once
// `teleop reset NODE`: an operator's request that a node clear its latched faults (the
// follower's reflexes) and follow its commands again, sent on the bus (msg::ResetRequest).

#include <cstdint>
#include <optional>
#include <string>

namespace teleop::launcher {

struct ResetOptions {
  /// The node to reset, by name.
  std::string target;
  /// A node configuration whose transport section (domain, discovery, security) to use; empty:
  /// the defaults on `domain_id`.
  std::string config_path;
  std::optional<int> domain_id;
  /// How long to wait for the node's reader to match and acknowledge [s].
  double timeout_s = 5.0;
};

/// Sends the request and waits until the target's reader has acknowledged it. Returns false when
/// no reader matched or acknowledged within the timeout. Throws ConfigError on a bad config.
bool send_reset(const ResetOptions& options);

}  // namespace teleop::launcher
