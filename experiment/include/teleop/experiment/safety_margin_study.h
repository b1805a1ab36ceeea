#pragma once
// PARTI §3.1, Fig. 5: collision avoidance by safety margins only the twin sees. An operator drives
// the two hands of the simulated two-arm body (the "physical" robot) into each other; the twin,
// coupled to it by eq. 2 and with margin spheres around both end effectors, renders its constraint
// torque back on it (eq. 3, low-passed). We record the distances over time: the twin's margin
// spheres (what the paper's Fig. 5 plots), the same spheres carried on the physical robot's own
// kinematics, and the physical arms' own geometry (which must never touch).
// `teleop fidelity-study safety_margins`; docs/fidelity.md.

#include <string>
#include <vector>

namespace teleop::experiment {

/// One variant of the scenario (the study runs several side by side).
struct SafetyMarginCase {
  std::string name;
  double activation_m = 0.0;  ///< twin::TwinModelConfig::margin_activation_m
};

struct SafetyMarginScenario {
  std::string name = "safety_margins";
  std::string model_path;  ///< the two-arm body (dual_arm.xml: left_/right_ link7, ee_site)
  std::string keyframe = "home";
  double sphere_radius_m = 0.08;
  double coupling_stiffness_nm_per_rad = 1000;  ///< K of eq. 2
  double coupling_damping_nms_per_rad = 20;     ///< D of eq. 2
  double feedback_gain = 1.0;                   ///< lambda of eq. 3
  double lowpass_hz = 50.0;                     ///< the rendered torque's IIR filter
  double push_n = 15.0;                         ///< the operator's force on each hand, towards the other
  double operator_damping_nms_per_rad = 6.0;    ///< the operator's arm damping the device's joints
  double duration_s = 3.0;
  double rest_window_s = 0.5;  ///< "at rest": the last this much of the run
  double trace_period_s = 0.005;
  std::vector<SafetyMarginCase> cases{{"touch", 0.0}};
};

/// Reads `safety_margin_study:` from a study file. Throws ConfigError naming file and key.
SafetyMarginScenario load_safety_margin_study(const std::string& path);

/// The distances of one case every trace_period_s [m] (negative: penetration).
struct SafetyMarginTrace {
  std::vector<double> t_s;
  std::vector<double> twin_margin_m;      ///< the twin's two margin spheres (Fig. 5's distance)
  std::vector<double> physical_margin_m;  ///< the same spheres on the physical robot's kinematics
  std::vector<double> arms_m;             ///< the physical arms' own geometry (links 6 and 7)
};

struct SafetyMarginResult {
  SafetyMarginCase config;
  double min_twin_margin_m = 1.0;
  double min_physical_margin_m = 1.0;
  double rest_twin_margin_m = 1.0;      ///< mean over the rest window
  double rest_physical_margin_m = 1.0;  ///< mean over the rest window
  double min_arms_m = 1.0;
  double first_contact_s = -1.0;  ///< when the twin's spheres first came within the activation distance
  int warnings = 0;
  SafetyMarginTrace trace;
};

/// Runs one case for `scenario.duration_s` at the model's 1 ms step. `feedback_gain` overrides
/// the scenario's lambda (0: nothing rendered, the margins are crossed).
SafetyMarginResult run_safety_margin_case(const SafetyMarginScenario& scenario, const SafetyMarginCase& c,
                                          double feedback_gain);

struct SafetyMarginStudyResult {
  std::vector<SafetyMarginResult> cases;
  std::string out_dir;
  std::string trace_csv;
  std::string markdown;
  std::string plot_error;
};

/// Every case, the trace CSV, the Markdown report (beside PARTI's Fig. 5) and the figure.
SafetyMarginStudyResult run_safety_margin_study(const SafetyMarginScenario& scenario, const std::string& out_dir,
                                                bool plots);

/// The report: per case the distances at impact and at rest, beside the paper's "≥ 0".
std::string format_safety_margin_markdown(const SafetyMarginScenario& scenario,
                                          const std::vector<SafetyMarginResult>& cases);

}  // namespace teleop::experiment
