#include "doctor_command.h"

#include <unistd.h>

#include <cstdio>

#include "teleop/common/config.h"
#include "teleop/common/data_paths.h"
#include "teleop/doctor/checks.h"
#include "teleop/doctor/host_reader.h"

namespace teleop::cli {
namespace {

// a node config's name (config/nodes), else a scenario's, else the path as given
std::string resolve_node_or_scenario(const std::string& name_or_path) {
  try {
    return resolve_config("nodes", name_or_path);
  } catch (const ConfigError&) {
    return resolve_config("scenarios", name_or_path);
  }
}

}  // namespace

DoctorCommand::DoctorCommand(CLI::App& app)
    : command_(app.add_subcommand("doctor", "check what a 1 kHz node needs of this host (real-time kernel, "
                                            "limits, governor, clock sync, CAN buses, input devices, DDS "
                                            "interfaces, the package's provisioning) and say how to fix each miss")) {
  command_->add_option("configs", configs_,
                       "node configs or scenarios (files, or names in config/nodes or config/scenarios) whose "
                       "needs to check: their realtime mode and priority, CAN buses and bitrates, DDS interfaces");
  command_->add_option("--root", root_, "read /proc, /sys, /dev and /etc under this folder (a copy of another host's)")
      ->check(CLI::ExistingDirectory);
}

std::optional<int> DoctorCommand::run() const {
  if (!command_->parsed()) return std::nullopt;
  doctor::HostNeeds needs;
  try {
    std::vector<std::string> files;
    for (const std::string& c : configs_) files.push_back(resolve_node_or_scenario(c));
    needs = doctor::needs_of(files);
  } catch (const ConfigError& e) {
    std::fprintf(stderr, "teleop doctor: %s\n", e.what());
    return 2;
  }
  char host[256] = {};
  ::gethostname(host, sizeof(host) - 1);
  const doctor::HostFacts facts = doctor::read_host(needs, root_);
  const std::vector<doctor::Finding> findings = doctor::check_host(facts, needs);
  std::printf("teleop doctor: host %s, kernel %s; %zu node%s checked\n%s", host, facts.kernel.release.c_str(),
              needs.realtime.size(), needs.realtime.size() == 1 ? "" : "s", doctor::findings_text(findings).c_str());
  const int status = doctor::exit_code(findings);
  std::printf(status == 0 ? "teleop doctor: every node the configs describe can run here\n"
                          : "teleop doctor: a node the configs describe could not run here (FAIL above)\n");
  return status;
}

}  // namespace teleop::cli
