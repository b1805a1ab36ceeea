#pragma once
// How good is the twin? The coupling thesis's accuracy study
// (shared/papers/justin-controller-simulation-coupling.md §4.1-4.3, §4.5) on the Panda-class arm:
// a "real" robot (the nominal model perturbed within docs/models.md's uncertainty, with noisy
// sensors: sim/plant_perturbation.h) runs a controller through the poses and the movements
// between them; its commands are recorded and replayed in lock-step (one controller step, one
// 1 ms model step, strictly alternating) into the nominal simulation, driven by the same
// controller code; the two runs are compared by the thesis's metrics, per pose and movement.
// `teleop fidelity-study fidelity`; docs/fidelity.md.

#include <cstdint>
#include <string>
#include <vector>

#include "teleop/control/controllers.h"
#include "teleop/experiment/metrics.h"
#include "teleop/sim/plant_perturbation.h"

namespace teleop::experiment {

/// The thesis's two controllers (§3.5): "state space" (a stiff joint PD, control::PositionPd)
/// and joint impedance with the controller's model's gravity (control::JointImpedance); and
/// PARTI's eq. 4, task-space impedance with nullspace (control::CartesianImpedance: the PARTI
/// twin study's, parti_twin_study.h).
enum class FidelityController { kStateSpace, kJointImpedance, kCartesianImpedance };
const char* controller_name(FidelityController controller);

struct FidelityPose {
  std::string name;
  control::JointVector q_rad = control::JointVector::Zero();
};

/// A run through poses: the model, and the poses in turn, at rest at each.
struct FidelitySequence {
  std::string name;
  std::string model_path;
  std::vector<std::string> path;  ///< pose names: the start, then each movement's goal
  /// A sequence made to touch the world (its poses and movements stay out of the tables; it gives
  /// the real-time factor in contact).
  bool contact = false;
};

struct FidelityStudyConfig {
  std::string name;
  std::string file;
  std::string ee_site = "ee_site";
  std::vector<uint64_t> seeds;
  std::vector<FidelityPose> poses;
  std::vector<FidelitySequence> sequences;
  double move_s = 3.0;
  double hold_s = 2.0;
  double pose_window_s = 0.5;
  double movement_before_s = 0.2;
  double movement_after_s = 0.4;
  double trace_period_s = 0.01;
  control::PositionPd::Gains state_space;
  control::JointImpedance::Gains joint_impedance;
  control::CartesianImpedance::Gains cartesian_impedance;
  sim::PerturbationSpec perturbation;
  sim::SensorNoiseSpec sensor_noise;

  /// The pose of that name (throws std::out_of_range naming it).
  const FidelityPose& pose(const std::string& name) const;
};

/// Reads a study file (`fidelity_study:` section). Throws ConfigError naming the file and key
/// (a pose outside the model's joint ranges, an unknown pose in a path, fewer than one seed...).
FidelityStudyConfig load_fidelity_study(const std::string& path);

/// A stretch of a run the thesis evaluates: a pose held (its last pose_window_s) or a movement
/// (from movement_before_s before it starts to movement_after_s after it ends).
struct FidelitySegment {
  std::string name;  ///< "ready" or "zero_to_ready"
  bool movement = false;
  Window window;
  Summary q_rmse_deg;      ///< eq. 4.2 over the joints, per sample
  Summary tau_rmse_nm;     ///< eq. 4.2 on the measured link-side torques
  Summary ee_position_cm;  ///< eq. 4.4
  Summary ee_rotation;     ///< eq. 4.5 (dimensionless)
  /// The largest single-joint |error|: of a movement at any sample of its window; of a pose
  /// averaged over its window first (thesis §4.2.2: "averaged over five hundred samples").
  double q_max_joint_deg = 0.0;
  double tau_max_joint_nm = 0.0;
};

/// The per-sample signals of one comparison (every model step).
struct FidelitySignals {
  std::vector<double> t_s;
  std::vector<double> q_rmse_deg;
  std::vector<double> q_max_joint_deg;
  std::vector<double> tau_rmse_nm;
  std::vector<double> tau_max_joint_nm;
  std::vector<double> ee_position_cm;
  std::vector<double> ee_rotation;
};

/// One sequence under one controller on one "real" robot, and its replay.
struct FidelityRun {
  std::string sequence;
  bool contact = false;
  FidelityController controller = FidelityController::kStateSpace;
  uint64_t seed = 0;
  sim::AppliedPerturbation perturbation;
  std::vector<FidelitySegment> segments;
  FidelitySignals signals;
  /// The replay's simulated time over its computing time, over the steps without and with a
  /// contact in the simulation (NaN where there were none) [-].
  double rt_factor_free = 0.0;
  double rt_factor_contact = 0.0;
  size_t free_steps = 0;
  size_t contact_steps = 0;
  int mujoco_warnings = 0;  ///< of both simulations
};

/// The recorded command of one control step (thesis §3.3: mode and gains are the run's).
struct RecordedCommand {
  control::JointVector q_d = control::JointVector::Zero();
  control::JointVector dq_d = control::JointVector::Zero();
};

/// The measured trajectory of a run: every step's joint state after it and its link-side torque.
struct FidelityTrajectory {
  std::vector<control::JointVector> q_rad;
  std::vector<control::JointVector> dq_radps;
  std::vector<control::JointVector> tau_nm;
  double timestep_s = 0.0;
  size_t contact_steps = 0;
  double computing_s = 0.0;
  double contact_computing_s = 0.0;
  int mujoco_warnings = 0;
  sim::AppliedPerturbation perturbation;
};

/// The "real" run: the sequence's commands (minimum jerk between the poses, hold_s at each) on
/// the perturbed robot of `seed` with noisy sensors; `commands` receives what its controller was
/// given, step by step. Throws std::runtime_error when the model cannot be set up.
FidelityTrajectory run_real(const FidelityStudyConfig& config, const FidelitySequence& sequence,
                            FidelityController controller, uint64_t seed, std::vector<RecordedCommand>& commands);
/// The replay: `commands` into the nominal model in lock-step, from the same start; noise-free.
FidelityTrajectory replay(const FidelityStudyConfig& config, const FidelitySequence& sequence,
                          FidelityController controller, const std::vector<RecordedCommand>& commands);

/// Real against replay: run_real, replay and the thesis's metrics per pose and movement.
FidelityRun run_fidelity_case(const FidelityStudyConfig& config, const FidelitySequence& sequence,
                              FidelityController controller, uint64_t seed);

/// The thesis's tables' cells for one controller and poses or movements (§4.3): the mean over the
/// segments of each one's mean, the sd among those means, and the maximum: for movements the
/// largest value at any sample ("the highest peak of the error term at any point in time in any
/// movement"), for poses the largest pose's mean (each pose averaged over its window, §4.2.2).
struct FidelityAggregate {
  double mean = 0.0;
  double sd = 0.0;
  double max = 0.0;
};
struct FidelityCell {
  FidelityAggregate q_rmse_deg;
  double q_max_joint_deg = 0.0;
  FidelityAggregate tau_rmse_nm;
  double tau_max_joint_nm = 0.0;
  FidelityAggregate ee_position_cm;
  FidelityAggregate ee_rotation;
};
/// Aggregates the table segments (not those of contact sequences) of `run` that are movements
/// (or poses).
FidelityCell aggregate(const FidelityRun& run, bool movements);

struct FidelityStudyOptions {
  std::string out_dir;                 ///< CSVs, Markdown and figures; default: a new folder in /tmp
  std::vector<uint64_t> seeds;         ///< instead of the file's
  std::vector<std::string> sequences;  ///< only these (empty: all)
  bool plots = true;
};

struct FidelityStudyResult {
  std::vector<FidelityRun> runs;
  std::string out_dir;
  std::string segments_csv;  ///< one row per run and segment: the summaries
  std::string runs_csv;      ///< one row per run: real-time factors, warnings, the perturbation
  std::string trace_csv;     ///< the signals every trace_period_s (the figures' input)
  std::string markdown;      ///< Tables 4.1 and 4.2 in shape, the thesis's numbers beside ours
  std::string plot_error;    ///< why no figures were drawn ("" when they were, or not asked for)
  /// Every run without a MuJoCo warning.
  bool sound() const;
};

/// Runs every sequence x controller x seed, writes the CSVs, the report and (unless
/// options.plots is false) the figures. Throws std::runtime_error when an output cannot be
/// written or a run cannot be set up; a failure to draw is reported in plot_error.
FidelityStudyResult run_fidelity_study(const FidelityStudyConfig& config, const FidelityStudyOptions& options);

/// The report: Tables 4.1 and 4.2 in the thesis's shape (ours: the mean over the seeds and their
/// range), the end-effector errors, the real-time factors, and the per-movement detail.
std::string format_fidelity_markdown(const FidelityStudyConfig& config, const std::vector<FidelityRun>& runs);

}  // namespace teleop::experiment
