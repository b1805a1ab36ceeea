#pragma once
// The wiping study of the coupling thesis (shared/papers/justin-controller-simulation-coupling.md
// §4.4, Tables 4.3 and 4.4) on the Panda-class arm of scene_wiping.xml: the wiper is held at an
// uncertain x-angle and the panel stands at an uncertain height; a plan made for one assumed
// angle and height commands the hand (the flange, not the tool) through three wipes across the
// panel under Cartesian impedance; a grid of angles x heights is simulated, its cells in parallel
// worker processes. Per cell: which wipes touched the panel (Table 4.3) and the per-joint peaks of
// the estimated external torque (Table 4.4). `teleop fidelity-study wiping`; docs/fidelity.md.

#include <string>
#include <vector>

#include "teleop/control/types.h"
#include "teleop/twin/twin_model_config.h"

namespace teleop::experiment {

/// A swept quantity of the world: the parameter kind it sets (parameter_sweep_config.h's
/// `set`, e.g. "body_angle_x:wiper"), its grid values and the value the plan assumed.
struct WipingParameter {
  std::string name;
  std::string set;
  std::vector<double> values;
  double planned = 0.0;
};

/// The motion the plan commands: the tool's path in the panel's frame (u across the panel,
/// horizontal; v up its slope; n its outward normal), carried over to the hand through the
/// planned wiper pose.
struct WipingPlan {
  /// The tool held tilted about its blade (its x axis, laid along v) away from flat on the panel:
  /// the blade's edge meets the surface, and the wiper's x-angle moves that edge along n [rad].
  double tool_lean_rad = -0.5;
  /// Per wipe, how far behind the planned surface the tool site is commanded (the contact force
  /// is set by it, thesis §4.4.1) [m]; its size is the number of wipes.
  std::vector<double> press_depth_m{0.006, 0.006, 0.004};
  double stroke_length_m = 0.30;   ///< along u, centred on the panel
  double stroke_spacing_m = 0.08;  ///< along v between neighbouring wipes
  double hover_m = 0.04;           ///< above the surface before and after each wipe
  double reach_s = 2.0;            ///< from the start pose to above the first wipe
  double press_s = 0.8;            ///< down onto the panel
  double stroke_s = 1.5;           ///< across it
  double lift_s = 0.5;             ///< up again
  double shift_s = 0.8;            ///< to above the next wipe
  double settle_s = 0.5;           ///< after the last
};

struct WipingStudyConfig {
  std::string name;
  std::string file;
  twin::TwinModelConfig model;
  std::string hand_site = "ee_site";    ///< the commanded frame: the flange
  std::string tool_site = "tool_site";  ///< the wiping face's centre
  std::string panel_geom = "panel";     ///< a box: its +z face the surface, its x axis up the slope
  WipingParameter wiper_angle;          ///< the sweep's rows (Table 4.3's)
  WipingParameter panel_height;         ///< its columns
  WipingPlan plan;
  double translational_stiffness_n_per_m = 1500.0;
  double rotational_stiffness_nm_per_rad = 60.0;
  /// K_O of the momentum observer that estimates the external torques (PARTI eqs. 6-7) [1/s].
  double observer_gain_per_s = 100.0;
  /// A wipe touched the panel when the contact pair's force exceeded this at some step [N].
  double contact_force_n = 1.0;
  int jobs = 2;  ///< worker processes
};

/// Reads a study file (`wiping_study:` section). Throws ConfigError naming the file and key.
WipingStudyConfig load_wiping_study(const std::string& path);
/// Whether the file at `path` holds a `wiping_study:` section (else another study's).
bool is_wiping_study(const std::string& path);

/// One wipe: its window runs from the press down to the end of the lift.
struct WipeOutcome {
  bool contact = false;
  int contact_steps = 0;
  /// the contact pair's force: its largest at any step (impacts included) and its mean over the
  /// steps in contact [N]
  double peak_force_n = 0.0;
  double mean_force_n = 0.0;
  /// max |tau_ext| per joint over the window: the momentum observer's estimate from the joint
  /// state and the commanded torque (what the thesis's controller computes) [N m]
  control::JointVector tau_ext_peak_nm = control::JointVector::Zero();
  /// max |qfrc_constraint| per joint over the window: the simulation's own [N m]
  control::JointVector constraint_peak_nm = control::JointVector::Zero();
};

/// One cell of the grid.
struct WipingCell {
  double wiper_angle_rad = 0.0;
  double panel_height_m = 0.0;
  std::vector<WipeOutcome> wipes;
  /// max |tau_ext| per joint outside the wipes, from the first wipe on (between the wipes and
  /// after the last; the reach to the panel left out): the estimate's level in free motion (the
  /// thesis's "deviations outside of contact phases") [N m]
  control::JointVector free_tau_ext_peak_nm = control::JointVector::Zero();
  double sim_time_s = 0.0;
  double wall_time_s = 0.0;
  int mujoco_warnings = 0;
  std::string error;  ///< empty when the cell ran
  int contacts() const;
};

/// The header of a cell's trace (kTraceColumns): every 10 ms the estimated external torque of
/// each joint, the contact force and the hand's height (the thesis's Figs. 4.13 and 4.15).
extern const char* const kWipingTraceColumns;

/// Simulates one cell; with a `trace_path`, writes its trace there as CSV rows without a header.
/// Never throws: a failure is reported in `error`.
WipingCell run_wiping_cell(const WipingStudyConfig& config, double wiper_angle_rad, double panel_height_m,
                           const std::string& trace_path = "");

/// Every cell, the angle varying slowest, in config.jobs worker processes (a cell whose worker
/// died has that error). With a `trace_csv` path, writes every cell's trace into it, in grid
/// order under one header. Forks; throws std::runtime_error when no worker can be started.
std::vector<WipingCell> run_wiping_sweep(const WipingStudyConfig& config, const std::string& trace_csv = "");

struct WipingStudyOptions {
  std::string out_dir;  ///< default: a new folder in /tmp
  int jobs = 0;         ///< instead of the file's (0: the file's)
  bool plots = true;
};

struct WipingStudyResult {
  std::vector<WipingCell> cells;
  int jobs = 0;
  double wall_time_s = 0.0;  ///< the whole sweep
  std::string out_dir;
  std::string wipes_csv;   ///< one row per cell and wipe (deterministic)
  std::string timing_csv;  ///< per cell wall time, and the sweep's
  std::string trace_csv;   ///< every cell's torques over time (deterministic)
  std::string markdown;    ///< Tables 4.3 and 4.4 in shape, the thesis's beside ours
  std::string plot_error;  ///< why no figures were drawn ("" when they were, or not asked for)
  /// Every cell ran, without a MuJoCo warning.
  bool sound() const;
};

/// Runs the sweep and writes the CSVs, the report and (unless options.plots is false) the
/// figure. Throws std::runtime_error when an output cannot be written.
WipingStudyResult run_wiping_study(WipingStudyConfig config, const WipingStudyOptions& options);

/// The report: Table 4.3 (wipes in contact per cell) and Table 4.4 (per-joint torque peaks per
/// cell) in the thesis's shape, with its tables and the real robot's peaks beside ours.
std::string format_wiping_markdown(const WipingStudyConfig& config, const std::vector<WipingCell>& cells);
/// One row per cell and wipe.
std::string format_wiping_csv(const std::vector<WipingCell>& cells);

}  // namespace teleop::experiment
