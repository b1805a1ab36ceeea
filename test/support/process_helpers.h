#pragma once
// Helpers for tests that run nodes as real processes.

#include <chrono>
#include <optional>
#include <string>
#include <vector>

#include "teleop/launcher/child_process.h"
#include "teleop/transport/participant_config.h"

namespace teleop::test {

/// Path of a built executable (bin directory of this build).
std::string bin(const std::string& name);
/// Path inside the source tree.
std::string source(const std::string& relative);

/// A DDS domain id no other concurrently running test process uses.
int unique_domain();

/// A participant of the test itself on the nodes' `domain` (UDP, no shared memory: it sees the
/// bus as the nodes see each other), named `name`.
transport::ParticipantConfig bus_participant(int domain, const std::string& name);

/// A fresh, empty directory for this test.
std::string make_temp_dir();
void write_file(const std::string& path, const std::string& text);
std::string read_file(const std::string& path);
/// A shipped node config (config/nodes/<name>) copied into `dir` with its model paths made
/// absolute and each (from, to) edit applied once; throws when an edit's text is missing.
std::string config_copy(const std::string& dir, const std::string& name,
                        const std::vector<std::pair<std::string, std::string>>& edits);

/// One process test's folder and domain: every node started with args() writes its report and
/// trace there under its tag, and no other test's nodes share the domain.
struct ProcessSite {
  std::string dir = make_temp_dir();
  int domain = unique_domain();
  /// `teleop_<node> --config <config> --domain <domain>`, report and trace under `tag`.
  std::vector<std::string> args(const std::string& node, const std::string& config, const std::string& tag) const;
  std::string report_path(const std::string& tag) const { return dir + "/" + tag + ".yaml"; }
  std::string trace_path(const std::string& tag) const { return dir + "/" + tag + ".csv"; }
};

struct ProcessResult {
  std::optional<int> exit_status;  ///< nullopt: still running at the timeout, then killed
  std::string output;              ///< stdout and stderr
};

/// Runs a command to completion (killing it after `timeout`) and captures its output.
ProcessResult run_process(const std::vector<std::string>& argv, std::chrono::seconds timeout);

/// A started process whose output is collected while the test waits.
class RunningProcess {
 public:
  explicit RunningProcess(const std::vector<std::string>& argv);
  /// Collects output for `duration`.
  void run_for(std::chrono::milliseconds duration);
  /// Collects output until `text` appears (true) or `timeout` passes (false).
  bool wait_for_output(const std::string& text, std::chrono::seconds timeout);
  /// Sends `sig`, then waits for the exit while collecting output.
  std::optional<int> stop(int sig, std::chrono::seconds timeout);
  launcher::ChildProcess& process() { return process_; }
  const std::string& output() const { return output_; }

 private:
  void collect();
  launcher::ChildProcess process_;
  std::string output_;
};

}  // namespace teleop::test
