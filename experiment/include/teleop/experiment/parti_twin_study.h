#pragma once
// PARTI §3.2 (Figs. 6-7): the digital twin's fidelity with table contacts. A taught trajectory
// (Cartesian waypoints: fast free motion, down onto the table, pressing, sliding on it, lifting off)
// runs under PARTI's eq. 4 (control::CartesianImpedance) on the "real" robot (the nominal model
// perturbed, noisy sensors: sim/plant_perturbation.h); its commands are replayed in lock-step on
// the nominal twin. Over time: the end-effector pose error and the contact-wrench error of the twin
// against the real robot, and on the real robot the external-force estimators against the true
// contact force, per phase (free motion, contact, static contact).
// `teleop fidelity-study parti_twin`; docs/fidelity.md.

#include <cstdint>
#include <string>
#include <vector>

#include "teleop/control/controllers.h"
#include "teleop/sim/plant_perturbation.h"

namespace teleop::experiment {

/// A taught waypoint: the end effector's position, reached by a minimum-jerk move of move_s, then
/// held hold_s. The orientation stays the start's.
struct PartiWaypoint {
  std::string name;
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();
  double move_s = 1.0;
  double hold_s = 0.0;
};

struct PartiTwinConfig {
  std::string name;
  std::string file;
  std::string model_path;
  std::string ee_site = "ee_site";
  std::string keyframe;  ///< the start pose (also the nullspace rest pose)
  std::vector<uint64_t> seeds;
  double start_hold_s = 1.0;
  std::vector<PartiWaypoint> waypoints;
  control::CartesianImpedance::Gains gains;
  double observer_gain_per_s = 100.0;  ///< K_O of eq. 7, every joint
  double direct_gamma = 0.1;           ///< gamma of eq. 5 (0.1 at 1 ms: the observer's bandwidth)
  /// Static contact: in contact and the end effector slower than this [m/s].
  double static_speed_mps = 0.005;
  double trace_period_s = 0.01;
  sim::PerturbationSpec perturbation;
  sim::SensorNoiseSpec sensor_noise;
};

/// Reads `parti_twin_study:`. Throws ConfigError naming file and key.
PartiTwinConfig load_parti_twin_study(const std::string& path);

/// The estimators compared (docs/fidelity.md, "PARTI's direct estimator").
enum PartiEstimator : int {
  kObserver = 0,        ///< momentum observer (eqs. 6-8) on the measured link torque
  kPartiLink = 1,       ///< eq. 5 with tau_d = 0, tau_m = tau_J: g(q) - tau_J
  kPartiCommand = 2,    ///< eq. 5 with tau_d = the control law's torque beyond gravity, tau_m = tau_J
  kDirectInertial = 3,  ///< the direct estimator with M ddq + n (control::DirectEstimator)
  kEstimatorCount = 4
};
const char* estimator_name(int estimator);

enum PartiPhase : int { kFree = 0, kContact = 1, kStaticContact = 2, kPhaseCount = 3 };
const char* phase_name(int phase);

/// Mean and maximum of an error over the samples of a phase.
struct PhaseError {
  double mean = 0.0;
  double max = 0.0;
  size_t samples = 0;
};

/// One seed's run and replay, every step's signals (1 ms).
struct PartiTwinRun {
  uint64_t seed = 0;
  std::vector<double> t_s;
  std::vector<int> phase;              ///< PartiPhase of the real robot (static contact counts as contact too)
  std::vector<double> position_mm;     ///< |p_real - p_twin|, end effector
  std::vector<double> rotation_mrad;   ///< angle of R_real R_twin^T
  std::vector<double> force_error_n;   ///< |F_real - F_twin|, the true contact forces at the end effector
  std::vector<double> moment_error_nm; ///< the same for the moments about the end effector
  std::vector<double> f_true_z_n;      ///< the real robot's contact force, z (up)
  std::vector<double> f_twin_z_n;
  std::vector<double> f_estimate_z_n[kEstimatorCount];
  std::vector<double> estimate_error_n[kEstimatorCount];  ///< |F_est - F_true| on the real robot
  PhaseError position[kPhaseCount];
  PhaseError force[kPhaseCount];
  PhaseError estimator[kEstimatorCount][kPhaseCount];
  double peak_force_n = 0.0;          ///< the real robot's largest contact force (the touchdown's impact)
  double static_force_n = 0.0;        ///< its mean contact force in static contact
  int mujoco_warnings = 0;
};

/// Runs the trajectory on the real robot of `seed`, replays it on the twin, evaluates.
PartiTwinRun run_parti_twin_case(const PartiTwinConfig& config, uint64_t seed);

struct PartiTwinResult {
  std::vector<PartiTwinRun> runs;
  std::string out_dir;
  std::string trace_csv;
  std::string phases_csv;
  std::string markdown;
  std::string plot_error;
};

/// Every seed, the CSVs (trace every trace_period_s, per phase), the report, the figures.
PartiTwinResult run_parti_twin_study(const PartiTwinConfig& config, const std::vector<uint64_t>& seeds,
                                     const std::string& out_dir, bool plots);

/// The report: per phase the twin's errors and the estimators' errors (mean over the seeds and their
/// range), beside what PARTI's §3.2 says.
std::string format_parti_twin_markdown(const PartiTwinConfig& config, const std::vector<PartiTwinRun>& runs);

}  // namespace teleop::experiment
