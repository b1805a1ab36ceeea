#pragma once
// Teleop nodes as real processes on the hosts of a NetnsNetwork: each node's config is its
// shipped config (config/nodes/<role>.yaml) with the transport section a test gives it.

#include <yaml-cpp/yaml.h>

#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "netns_network.h"
#include "process_helpers.h"
#include "teleop/runtime/node_report.h"

namespace teleop::test {

/// Changes a node's config before it is written (e.g. a sentinel joint value).
using ConfigEdit = std::function<void(YAML::Node& root)>;

/// Nodes of one test run. Stops (SIGKILL) whatever still runs when destroyed.
class NetnsNodes {
 public:
  explicit NetnsNodes(const NetnsNetwork& network);

  /// Starts `role` (leader, follower, twin) on `host` for `duration_s` with `transport` as its
  /// transport section, writing its report to report_path(role). `name` defaults to the role.
  RunningProcess& start(const std::string& role, int host, const YAML::Node& transport, double duration_s,
                        const ConfigEdit& edit = {}, const std::string& name = "");
  /// Starts any program on `host` (a discovery server, a probe).
  RunningProcess& start_program(const std::string& name, int host, const std::vector<std::string>& argv);
  /// Waits for `name` to exit; nullopt if it still runs after `timeout`.
  std::optional<int> wait_exit(const std::string& name, std::chrono::seconds timeout);
  RunningProcess& process(const std::string& name) { return *processes_.at(name); }
  /// Collects every process's output for `duration` (keeps their pipes from filling).
  void run_for(std::chrono::milliseconds duration);

  std::string report_path(const std::string& name) const { return dir_ + "/" + name + ".report.yaml"; }
  runtime::NodeReport report(const std::string& name) const { return runtime::read_report(report_path(name)); }
  /// Everything the processes printed, for failure messages.
  std::string outputs() const;
  const std::string& dir() const { return dir_; }
  int domain() const { return domain_; }

 private:
  std::string write_config(const std::string& role, const std::string& name, const YAML::Node& transport,
                           const ConfigEdit& edit) const;

  const NetnsNetwork& network_;
  std::string dir_;
  int domain_;
  std::map<std::string, std::unique_ptr<RunningProcess>> processes_;
};

/// One received topic of a report (fails the test when it is not there).
const runtime::ReceivedTopic& received(const runtime::NodeReport& report, const std::string& topic);
/// One counter of a report (fails the test when it is not there).
double counter(const runtime::NodeReport& report, const std::string& name);

}  // namespace teleop::test
