#pragma once
// PNG figures of runs and experiments (docs/plots.md): the python package scripts/teleop_plot
// (matplotlib, Agg backend: no display) run as a child process by `teleop plot` and
// `teleop experiment`.

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace teleop::experiment {

/// What keeps figures from being drawn: a run dir without traces, no python3 with matplotlib,
/// no plotting package, the package failing. The message names the dir or says what to install.
class PlotError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The interpreter and the package that draw the figures.
struct PlotTool {
  std::string python;       ///< a python3 that imports matplotlib
  std::string package_dir;  ///< scripts/teleop_plot, or <prefix>/share/teleop/teleop_plot installed
};

/// Finds the package (beside an installed teleop: <exe>/../share/teleop/teleop_plot; else the
/// source tree this was built from; else the install prefix it was configured with) and a python3
/// that imports matplotlib ($TELEOP_PYTHON if set; else python3 on PATH, then /usr/bin/python3, the
/// one Debian's python3-matplotlib is for). Throws PlotError saying what is missing and how to
/// install it.
PlotTool find_plot_tool();

/// The traces of the run in `run_dir`: its `*.csv` files whose header begins with `t_s`, sorted.
/// Throws PlotError naming the dir when it does not exist or holds no trace.
std::vector<std::string> run_traces(const std::string& run_dir);

/// What a run's figures mark: the operator's start, read from the trace of node `leader` (its
/// operator_s clock), and windows [s after it] shaded with their labels. No leader: no marks.
struct RunMarks {
  std::string leader;
  std::vector<std::pair<std::string, std::pair<double, double>>> windows;
};

/// Writes the figures of the run in `run_dir` (run_traces() must find some) into `out_dir`,
/// created if needed, with `marks`. Throws PlotError.
void plot_run(const PlotTool& tool, const std::string& run_dir, const std::string& out_dir, const RunMarks& marks = {});

/// Writes the figures of a recording exported as CSV into `csv_dir` (tools' export_csv) into
/// `out_dir`: each joint state topic's positions, each wrench's force and torque, each joint
/// torque topic's torques. Throws PlotError.
void plot_recording_csv(const PlotTool& tool, const std::string& csv_dir, const std::string& out_dir);

/// Writes one figure per metric of an experiment's results CSV beside it, as
/// `<csv stem>_<metric>.png`, each metric of `limits` with its limit drawn (the stability
/// verdict's: stable at or below it). Throws PlotError.
void plot_results(const PlotTool& tool, const std::string& csv_path,
                  const std::vector<std::pair<std::string, double>>& limits = {});

/// Writes the hand study's figures of its trace CSV (docs/hand.md) into `out_dir`: the index
/// tip's force over time per run (the paper's Fig. 4) and two joints' positions (Figs. 5, 6).
/// Throws PlotError.
void plot_hand_study(const PlotTool& tool, const std::string& trace_csv, const std::string& out_dir);

/// Writes the fidelity study's figures (docs/fidelity.md) into `out_dir`: per movement, the joint,
/// torque and end-effector errors over time of both controllers (the thesis's Fig. 4.4), and the
/// contact sequence's. Throws PlotError.
void plot_fidelity_study(const PlotTool& tool, const std::string& trace_csv, const std::string& segments_csv,
                         const std::string& out_dir);

/// Writes the figures of a PARTI study (docs/fidelity.md) into `out_dir`: `kind` "margins" (the
/// distances over time, beside the paper's Fig. 5) or "twin" (the error norms and the estimators
/// over time, beside Figs. 6-7). Throws PlotError.
void plot_parti_study(const PlotTool& tool, const std::string& kind, const std::string& trace_csv,
                      const std::string& out_dir);

/// Writes the wiping study's figures (docs/fidelity.md) into `out_dir`: per wiper angle, the
/// per-joint external-torque peaks of each panel height (the thesis's Table 4.4 as bars), and
/// joints 0 and 3's torques over time (its Fig. 4.13). Throws PlotError.
void plot_wiping_study(const PlotTool& tool, const std::string& wipes_csv, const std::string& trace_csv,
                       const std::string& out_dir);

}  // namespace teleop::experiment
