#pragma once
// `teleop bag info|convert|repair|export`: the recordings' own commands (teleop/tools/bag_tools.h,
// teleop/tools/recording_csv.h).

#include <CLI/CLI.hpp>

#include <optional>
#include <string>
#include <vector>

namespace teleop::cli {

class BagCommands {
 public:
  /// Adds `bag` and its subcommands to `app`.
  explicit BagCommands(CLI::App& app);
  /// Runs the one that was parsed; nullopt when none was. Throws like the tools do.
  std::optional<int> run() const;

 private:
  CLI::App* info_ = nullptr;
  CLI::App* convert_ = nullptr;
  CLI::App* repair_ = nullptr;
  CLI::App* export_ = nullptr;
  std::string path_;
  std::string out_;
  std::vector<std::string> topics_;
};

}  // namespace teleop::cli
