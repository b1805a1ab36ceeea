#pragma once
// The subcommands that look at the bus: `teleop topic list|info|echo|hz` and `teleop monitor`
// (and `record`, `replay`, `bridge`). Each joins the domain the way a node config says.

#include <CLI/CLI.hpp>

#include <optional>

#include "teleop/bridge/bridge.h"
#include "teleop/tools/monitor.h"
#include "teleop/tools/recorder.h"
#include "teleop/tools/replayer.h"
#include "teleop/tools/topic_tools.h"

class BusCommands {
 public:
  /// Adds the subcommands to `app`.
  explicit BusCommands(CLI::App& app);
  /// Runs the one that was parsed; nullopt when none of them was. Throws like the tools do.
  std::optional<int> run();

 private:
  void add_bus_options(CLI::App* command);
  void add_record();
  void add_replay();
  void add_bridge();
  int run_record();
  int run_replay();
  int run_bridge();

  CLI::App* app_;
  teleop::tools::BusOptions bus_;
  CLI::App* list_ = nullptr;
  CLI::App* info_ = nullptr;
  CLI::App* echo_ = nullptr;
  CLI::App* hz_ = nullptr;
  CLI::App* monitor_ = nullptr;
  CLI::App* record_ = nullptr;
  CLI::App* replay_ = nullptr;
  CLI::App* bridge_ = nullptr;
  bool verbose_ = false;
  std::string topic_;
  teleop::tools::EchoOptions echo_options_;
  teleop::tools::HzOptions hz_options_;
  teleop::tools::MonitorOptions monitor_options_;
  std::optional<bool> lines_;
  teleop::tools::RecordOptions record_options_;
  teleop::tools::ReplayOptions replay_options_;
  teleop::bridge::BridgeOptions bridge_options_;
  std::string bridge_scene_;
};
