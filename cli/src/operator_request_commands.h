#pragma once
// The operator's requests to running nodes: `teleop reset NODE` (clear a latched reflex),
// `teleop estop [NODE]` (an emergency stop: every node, or one) and `teleop enable [NODE]` (the
// deliberate enable that alone ends a stop, docs/stop_chain.md).

#include <CLI/CLI.hpp>

#include <optional>
#include <string>

#include "teleop/launcher/operator_requests.h"

namespace teleop::cli {

class OperatorRequestCommands {
 public:
  /// Adds the subcommands to `app`.
  explicit OperatorRequestCommands(CLI::App& app);
  /// Sends the one that was parsed and says who acknowledged it; nullopt when none was parsed.
  std::optional<int> run() const;

 private:
  CLI::App* add(CLI::App& app, const char* name, const char* summary, launcher::BusRequestOptions& options,
                bool node_required);

  CLI::App* reset_;
  CLI::App* estop_;
  CLI::App* enable_;
  launcher::BusRequestOptions reset_options_;
  launcher::BusRequestOptions estop_options_;
  launcher::BusRequestOptions enable_options_;
  std::string origin_ = "teleop estop";
};

}  // namespace teleop::cli
