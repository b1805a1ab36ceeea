#include "plot_command.h"

#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "teleop/experiment/plots.h"
#include "teleop/tools/bag_tools.h"
#include "teleop/tools/recording_csv.h"

namespace teleop::cli {
namespace {

namespace fs = std::filesystem;

// the recording's topics as CSV into OUT/csv (tools' export_csv), then their figures into OUT
void plot_recording(const std::string& recording, const std::string& out_dir) {
  const std::string csv_dir = (fs::path(out_dir) / "csv").string();
  const tools::CsvExport exported = tools::export_csv(recording, csv_dir, {});
  for (const tools::CsvTopicFile& f : exported.files) {
    std::printf("teleop plot: exported %s (%llu rows)\n", f.path.c_str(), static_cast<unsigned long long>(f.rows));
  }
  experiment::plot_recording_csv(experiment::find_plot_tool(), csv_dir, out_dir);
}

}  // namespace

PlotCommand::PlotCommand(CLI::App& app)
    : command_(app.add_subcommand("plot", "write PNG figures of a run's traces (<node>.csv): positions, forces, "
                                          "TDPA energy, loop lateness, states; or of a recording's topics")) {
  command_->add_option("run_dir", run_dir_,
                       "a run's trace folder (teleop launch --trace-dir, or <report dir>/<run>/<profile> of an "
                       "experiment), or a recording (an MCAP file, a sqlite3 bag folder)")
      ->required();
  command_->add_option("-o,--out", out_dir_,
                       "folder for the figures (default: RUN_DIR; for a recording its path + '_plots', its "
                       "topics as CSV in OUT/csv)");
}

int PlotCommand::run() const {
  try {
    if (tools::is_recording(run_dir_)) {
      plot_recording(run_dir_, out_dir_.empty() ? tools::recording_stem(run_dir_) + "_plots" : out_dir_);
      return 0;
    }
    // the traces first: a wrong folder is named before python is even looked for
    experiment::run_traces(run_dir_);
    experiment::plot_run(experiment::find_plot_tool(), run_dir_, out_dir_.empty() ? run_dir_ : out_dir_);
    return 0;
  } catch (const std::runtime_error& e) {  // PlotError; a recording's BagError, a CSV not written
    std::fprintf(stderr, "teleop plot: %s\n", e.what());
    return 1;
  }
}

}  // namespace teleop::cli
