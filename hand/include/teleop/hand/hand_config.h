#pragma once
// The `hand:` section of the hand node's configuration (config/nodes/hand.yaml).

#include <string>

#include "teleop/common/config.h"
#include "teleop/hand/hand_adapter.h"

namespace teleop::hand {

struct HandNodeConfig {
  /// SocketCAN interface of the hand's bus (can0, vcan0).
  std::string interface = "vcan0";
  /// Everything the adapter needs; cycle_rate_hz is the node's rate_hz.
  HandAdapterConfig adapter;
  /// No HandCommand for this long: the hand holds its last targets and the node reports stale input.
  double command_timeout_s = 0.1;
};

/// Reads the `hand:` section (and node.rate_hz as the SYNC rate). Throws ConfigError naming
/// file, key and problem, including for an adapter configuration the adapter would refuse.
HandNodeConfig parse_hand_config(const ConfigNode& root);

}  // namespace teleop::hand
