#pragma once
// `teleop plot RUN_DIR|RECORDING [-o OUT_DIR]`: the figures of a run's traces, or of a recording's
// topics exported as CSV (docs/plots.md).

#include <CLI/CLI.hpp>

#include <string>

namespace teleop::cli {

class PlotCommand {
 public:
  /// Adds the subcommand to `app`.
  explicit PlotCommand(CLI::App& app);

  bool parsed() const { return command_->parsed(); }
  /// Writes the figures; prints what went wrong and returns 1 when it could not.
  int run() const;

 private:
  CLI::App* command_;
  std::string run_dir_;
  std::string out_dir_;
};

}  // namespace teleop::cli
