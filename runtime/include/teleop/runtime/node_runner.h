#pragma once
// The shared body of every node executable: command line, configuration, participant,
// fixed-rate loop, status publication, clean shutdown and the report.

#include <functional>
#include <memory>
#include <string>

#include <teleop/msg/status.h>

#include "teleop/common/config.h"
#include "teleop/runtime/node_config.h"
#include "teleop/runtime/node_logic.h"
#include "teleop/transport/participant.h"

namespace teleop::runtime {

/// What a node's logic is built from.
struct NodeContext {
  const NodeConfig& node;
  transport::Participant& participant;
};

/// Builds the logic once the participant exists.
using LogicBuilder = std::function<std::unique_ptr<NodeLogic>(NodeContext&)>;
/// Reads the role's own config sections (throwing ConfigError) and returns the builder; runs
/// before any DDS entity exists, so a bad config never reaches the network.
using LogicParser = std::function<LogicBuilder(const ConfigNode& root)>;

struct NodeDescription {
  msg::NodeRole role;
  /// "leader", "follower", "twin": the default node name and the role in reports.
  std::string role_name;
  /// One line for --help.
  std::string summary;
  LogicParser parse;
};

/// Runs a node to completion and returns the process exit code: 0 after a clean run,
/// 1 on a runtime failure, 2 on bad command line or configuration (one line on stderr naming
/// file, key and problem).
int run_node(int argc, char** argv, const NodeDescription& description);

/// Convenience for a logic class with `static Config parse_config(const ConfigNode&)` and a
/// constructor `Logic(Config, NodeContext&)`.
template <typename Logic>
LogicParser parser_for() {
  return [](const ConfigNode& root) -> LogicBuilder {
    auto config = Logic::parse_config(root);
    return [config](NodeContext& context) { return std::make_unique<Logic>(config, context); };
  };
}

}  // namespace teleop::runtime
