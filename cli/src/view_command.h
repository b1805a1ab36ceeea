#pragma once
// `teleop view`: the live 3D view of a node's scene posed from the bus, and `teleop render RUN_DIR`:
// a run's video from its traces (docs/view.md).

#include <CLI/CLI.hpp>

#include <optional>
#include <string>

#include "teleop/view/render_run.h"
#include "teleop/view/viewer.h"

namespace teleop::cli {

class ViewCommands {
 public:
  /// Adds the subcommands to `app`.
  explicit ViewCommands(CLI::App& app);
  /// Runs the one that was parsed; nullopt when none of them was. Prints what went wrong.
  std::optional<int> run();
  /// `teleop experiment --render`: adds the option to `experiment` (see render_experiment()).
  void add_experiment_option(CLI::App* experiment);
  /// Renders each run folder below `report_dir` (one with a follower.csv) when asked to; returns
  /// the number that failed.
  int render_experiment(const std::string& report_dir) const;

 private:
  void add_view(CLI::App& app);
  void add_render(CLI::App& app);

  CLI::App* view_ = nullptr;
  CLI::App* render_ = nullptr;
  view::ViewOptions view_options_;
  view::RenderOptions render_options_;
  bool no_twin_ = false;
  bool no_contacts_ = false;
  bool no_shadows_ = false;
  bool no_overlay_ = false;
  bool experiment_render_ = false;
};

}  // namespace teleop::cli
