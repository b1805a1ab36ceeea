#pragma once
// `teleop doctor [CONFIG|SCENARIO...]`: checks what the given nodes (default: none, the host
// alone) need of this host and says how to fix each miss (docs/provisioning.md). Exits 1 when a
// node the configs describe could not run here, 2 when a config is wrong.

#include <CLI/CLI.hpp>

#include <optional>
#include <string>
#include <vector>

namespace teleop::cli {

class DoctorCommand {
 public:
  explicit DoctorCommand(CLI::App& app);
  /// The exit status when `doctor` was parsed, else nullopt.
  std::optional<int> run() const;

 private:
  CLI::App* command_;
  std::vector<std::string> configs_;
  std::string root_ = "/";
};

}  // namespace teleop::cli
