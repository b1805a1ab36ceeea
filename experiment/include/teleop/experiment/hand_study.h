#pragma once
// The SVH hand study (shared/papers/svh-hand-gazebo-mujoco.md §IV) reproduced in MuJoCo: the
// UR5-class arm with the SVH-class hand moves from "home" to "test" (Table I) on a minimum-jerk
// joint trajectory under the paper's PD control, the index fingertip comes to rest against a
// panel, and while it rests there the joint positions and the tip force are recorded. The
// oscillation of each joint is the paper's eq. 3, the Mean Absolute Deviation from its 10-sample
// running mean, for each finger-link inertia setting (0.001, 0.01, 0.1 kg m^2), with the
// couplings as the mechanism (the model's equalities) or as servos. `teleop hand-study
// config/experiments/hand_contact.yaml`; docs/hand.md.

#include <string>
#include <vector>

#include "teleop/hand/position_control.h"

namespace teleop::experiment {

/// One simulation of the study.
struct HandStudyRun {
  std::string name;
  /// Diagonal inertia of every hand link a joint moves [kg m^2] (the paper's setting); 0: the
  /// model's own inertias.
  double link_inertia_kgm2 = 0.0;
  hand::CouplingMode coupling = hand::CouplingMode::kConstraint;
};

/// A pose the motion passes through at rest: a keyframe of the scene, reached in move_s.
struct HandStudyWaypoint {
  std::string keyframe;
  double move_s = 0.0;  ///< from the waypoint before (the first waypoint is the start: 0)
};

struct HandStudyConfig {
  std::string name;
  std::string file;
  std::string model_path;  ///< the scene, resolved relative to the study file
  /// The start, then the waypoints in turn, minimum jerk between each two; the last is the pose
  /// the study holds and every PD is designed at. One waypoint: no motion, start in contact.
  std::vector<HandStudyWaypoint> path;
  double settle_s = 2.0;          ///< at the goal before the recording window
  double record_s = 3.0;          ///< the window the MAD and the force statistics cover
  double sample_period_s = 0.01;  ///< a joint-state sample every this long (a multiple of the timestep)
  size_t mad_window = 10;         ///< samples in the running mean (the paper's 10)
  double arm_bandwidth_radps = 40.0;
  double hand_bandwidth_radps = 40.0;
  double damping_ratio = 1.0;
  double servo_bandwidth_radps = 200.0;  ///< the coupled joints' PD in the servo runs
  /// The hand motors' torque limit [N m]; 0: the model's (the emulated drive's 1.2 N m).
  double hand_torque_limit_nm = 0.0;
  /// The contact solver, when the study overrides the model's: "" (the model's), "pyramidal" or
  /// "elliptic" friction cones, and the no-slip iterations (-1: the model's).
  std::string friction_cone;
  int noslip_iterations = -1;
  std::vector<HandStudyRun> runs;

  /// The time the motion takes (the sum of the waypoints' move_s).
  double motion_s() const;
};

/// Reads a study file (`hand_study:` section). Throws ConfigError naming the file and key.
HandStudyConfig load_hand_study(const std::string& path);

/// The study's joints in the order of its tables: the paper's 15 of Tables II and III (in their
/// order: 9 motor joints, 6 arm joints), then the hand's 11 coupled joints.
const std::vector<std::string>& hand_study_joints();
/// How many of hand_study_joints() the paper's tables list (the first 15).
constexpr size_t kPaperTableJoints = 15;

struct HandStudyRunResult {
  HandStudyRun run;
  std::vector<double> t_s;                 ///< sample times from the start of the motion
  std::vector<std::vector<double>> q_rad;  ///< per joint of hand_study_joints(), one value per sample
  std::vector<double> tip_force_n;         ///< the index tip's touch sensor, per sample
  double record_begin_s = 0.0;             ///< the recording window: [record_begin_s, t_s.back()]
  std::vector<double> mad_rad;             ///< eq. 3 over the recording window, per joint
  double mad_paper_average_rad = 0.0;      ///< mean over the paper's 15 (its tables' "Average")
  double mad_max_rad = 0.0;                ///< max over all 26 joints
  double tip_force_mean_n = 0.0;           ///< in the recording window
  double tip_force_sd_n = 0.0;
  double tip_force_min_n = 0.0;
  double tip_force_max_n = 0.0;
  double first_contact_s = 0.0;            ///< first sample with a tip force (NaN: none)
  double coupling_residual_max_rad = 0.0;  ///< over the whole run, after every step
  int mujoco_warnings = 0;                 ///< MuJoCo's warning counters at the end
  /// Steps with a contact other than the index fingertip on the panel (a finger, the arm, the
  /// floor): 0 when the scene does what the study means.
  long foreign_contact_steps = 0;
  double wall_s = 0.0;  ///< the run's computing time
  /// A run that did what the study needs: no MuJoCo warning, no contact but the fingertip's, and
  /// the fingertip pressing the panel throughout the recording window.
  bool sound() const { return mujoco_warnings == 0 && foreign_contact_steps == 0 && tip_force_min_n > 0.0; }
};

/// Simulates one run (setup errors throw std::runtime_error naming the model).
HandStudyRunResult run_hand_study_case(const HandStudyConfig& config, const HandStudyRun& run);

struct HandStudyOptions {
  std::string out_dir;            ///< CSVs, Markdown and figures; default: a new folder in /tmp
  std::vector<std::string> runs;  ///< only these runs (empty: all)
  bool plots = true;
};

struct HandStudyResult {
  std::vector<HandStudyRunResult> runs;
  std::string out_dir;
  std::string mad_csv;     ///< run, inertia, coupling, joint, MAD
  std::string runs_csv;    ///< one row per run: force statistics, residual, warnings
  std::string trace_csv;   ///< the samples of every run (the figures' input)
  std::string markdown;    ///< the tables beside the paper's
  std::string plot_error;  ///< why no figures were drawn ("" when they were, or not asked for)
};

/// Runs the study's runs, writes the CSVs, the Markdown report and (unless options.plots is
/// false) the figures (tip force over time, as the paper's Fig. 4; two joints, as Figs. 5-6).
/// Throws std::runtime_error when an output cannot be written or a run cannot be set up; a
/// failure to draw is reported in plot_error, not thrown (the numbers are the result).
HandStudyResult run_hand_study(const HandStudyConfig& config, const HandStudyOptions& options);

/// The report: ours beside the paper's Tables II (Gazebo) and III (MuJoCo), the coupled joints,
/// and a line per run (tip force, coupling residual, MuJoCo warnings).
std::string format_hand_study_markdown(const HandStudyConfig& config, const std::vector<HandStudyRunResult>& runs);

}  // namespace teleop::experiment
