#include "operator_request_commands.h"

#include <cstdio>

#include "config_option.h"
#include "teleop/transport/topics.h"

namespace teleop::cli {

CLI::App* OperatorRequestCommands::add(CLI::App& app, const char* name, const char* summary,
                                       launcher::BusRequestOptions& options, bool node_required) {
  CLI::App* command = app.add_subcommand(name, summary);
  CLI::Option* node = command->add_option("node", options.target,
                                          node_required ? "the node's name (e.g. follower)"
                                                        : "the node's name (e.g. follower); none: every node");
  if (node_required) node->required();
  command->add_option("-c,--config", options.config_path,
                      "take domain, discovery and security from this node config (a file, or a name in config/nodes)")
      ->transform(named_config("nodes"))
      ->check(CLI::ExistingFile);
  command->add_option("--domain", options.domain_id, "DDS domain id (overrides the config)")->check(CLI::Range(0, 232));
  command->add_option("--timeout", options.timeout_s, "seconds to wait for the nodes to acknowledge")
      ->check(CLI::Range(0.1, 600.0));
  return command;
}

OperatorRequestCommands::OperatorRequestCommands(CLI::App& app)
    : reset_(add(app, "reset", "ask a node to clear its latched reflex and follow its commands again", reset_options_,
                 true)),
      estop_(add(app, "estop", "emergency stop: every node (or NODE) stops and stays stopped until `teleop enable`",
                 estop_options_, false)),
      enable_(add(app, "enable", "end an emergency stop: every node (or NODE) resumes", enable_options_, false)) {
  estop_->add_option("--origin", origin_, "what the stop comes from, for the nodes' logs (default: teleop estop)");
}

namespace {

int say(int acknowledged, const char* what, const launcher::BusRequestOptions& options, const char* topic) {
  const std::string whom = options.target.empty() ? "every node" : options.target;
  if (acknowledged > 0) {
    std::printf("%s sent to %s and acknowledged by %d reader%s\n", what, whom.c_str(), acknowledged,
                acknowledged == 1 ? "" : "s");
    return 0;
  }
  std::fprintf(stderr, "teleop: no reader of %s acknowledged the %s within %.1f s (is the node running on this domain?)\n",
               topic, what, options.timeout_s);
  return 1;
}

}  // namespace

std::optional<int> OperatorRequestCommands::run() const {
  using namespace transport::topics;
  if (reset_->parsed()) return say(launcher::send_reset(reset_options_), "reset", reset_options_, kResetRequest.name);
  if (estop_->parsed()) {
    return say(launcher::send_emergency_stop(estop_options_, true, origin_), "emergency stop", estop_options_,
               kEmergencyStop.name);
  }
  if (enable_->parsed()) {
    return say(launcher::send_emergency_stop(enable_options_, false, "teleop enable"), "enable", enable_options_,
               kEmergencyStop.name);
  }
  return std::nullopt;
}

}  // namespace teleop::cli
