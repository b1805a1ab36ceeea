#include "plot_command.h"

#include <cstdio>

#include "teleop/experiment/plots.h"

namespace teleop::cli {

PlotCommand::PlotCommand(CLI::App& app)
    : command_(app.add_subcommand("plot", "write PNG figures of a run's traces (<node>.csv): positions, forces, "
                                          "TDPA energy, loop lateness, states")) {
  command_->add_option("run_dir", run_dir_,
                       "a run's trace folder (teleop launch --trace-dir, or <report dir>/<run>/<profile> of an "
                       "experiment)")
      ->required();
  command_->add_option("-o,--out", out_dir_, "folder for the figures (default: RUN_DIR)");
}

int PlotCommand::run() const {
  try {
    // the traces first: a wrong folder is named before python is even looked for
    experiment::run_traces(run_dir_);
    experiment::plot_run(experiment::find_plot_tool(), run_dir_, out_dir_.empty() ? run_dir_ : out_dir_);
    return 0;
  } catch (const experiment::PlotError& e) {
    std::fprintf(stderr, "teleop plot: %s\n", e.what());
    return 1;
  }
}

}  // namespace teleop::cli
