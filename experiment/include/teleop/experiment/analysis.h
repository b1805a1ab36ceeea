#pragma once
// The metrics of one run, computed from the leader's and the follower's time traces.

#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "teleop/experiment/metrics.h"
#include "teleop/experiment/trace.h"
#include "teleop/box_task/box_task_metrics.h"

namespace teleop::experiment {

/// What the runs do, which decides the metrics: a single arm pressing a stiff wall (force and
/// tracking errors in the hold window) or the two-arm box task (docs/box_task.md).
enum class AnalysedTask { kStiffWall, kBoxTask };

/// The `analysis:` section of an experiment file. Times are seconds after the operator began
/// (operator_start_s: the leader's first row unless its operator waits to be in command).
struct AnalysisConfig {
  AnalysedTask kind = AnalysedTask::kStiffWall;
  std::string leader = "leader";
  std::string follower = "follower";
  /// kBoxTask: the arms, whose columns the traces prefix with "<arm>_", and where the box must
  /// end up (the shelf region of the scene named by analysis.scene).
  std::vector<std::string> arms;
  box_task::BoxRegion shelf{};
  double settle_s = 1.0;
  /// Stiff wall: the contact held; box task: the carry (MAD, stability).
  Window hold{6.0, 10.0};
  double stable_max_mad_rad = 1e-4;
  double stable_max_saturation = 0.01;
  /// Largest MAD of the follower's contact force [N] (chatter on the wall: contact made and lost
  /// within a few cycles, which the wall hides from the joint positions).
  double stable_max_force_mad_n = 0.1;
  /// Largest share of the follower's rows in safe hold (a run that sat in its watchdog's hold is
  /// not a stable run, whatever its joints did).
  double stable_max_safe_hold = 0.05;
  /// Every flow of the run must have matched within this many seconds of the operator's start,
  /// or the run is invalid (its operator moved before the robot followed); <0: settle_s.
  double max_flows_matched_s = -1.0;
};

/// Samples of the running average behind mad_rad (the MAD definition's window).
inline constexpr size_t kMadWindowSamples = 10;
/// torque_ratio at or above this counts as saturated.
inline constexpr double kSaturatedTorqueRatio = 0.999;

/// What one run measured. NaN where the traces hold no sample for a metric (e.g. a run shorter
/// than the hold window, or no TDPA).
struct RunMetrics {
  static constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
  double force_error_n = kNone;        ///< mean |f_felt - f_ext| in the hold window
  double force_felt_n = kNone;         ///< mean |f_felt| in the hold window
  double force_exerted_n = kNone;      ///< mean |f_ext| in the hold window
  double tracking_rmse_m = kNone;      ///< RMS |x_cmd - x| from settle_s to the end
  double tracking_hold_m = kNone;      ///< RMS |x_cmd - x| in the hold window
  double mad_rad = kNone;              ///< follower joints' MAD from their running mean, hold window, joint mean
  double force_mad_n = kNone;          ///< MAD of |f_ext| from its running mean, hold window
  double hold_ptp_m = kNone;           ///< norm of the per-axis peak-to-peak of the follower's x, hold window
  double tdpa_min_energy_j = kNone;    ///< minimum tdpa_w_j of both traces over the run
  double saturation_fraction = kNone;  ///< follower rows with torque_ratio >= kSaturatedTorqueRatio
  double safe_hold_fraction = kNone;   ///< follower rows in STATE_SAFE_HOLD
  double reflex_latches = kNone;       ///< times the follower's safety reflex latched (its `reflex` column rising)
  /// What tripped the first latch, as the follower's report's reflex_cause counts it
  /// (follower/safety_reflex.h: 1 joint torque, 2 force, 3 moment, 4 joint speed); 0: none.
  double reflex_cause = kNone;
  /// When every flow of the run had matched [s after the operator began]: the later of the
  /// leader's first `running` row (in command, its feedback fresh) and the follower's first
  /// command in force; infinity: never; NaN: the traces cannot say.
  double flows_matched_s = kNone;
  // the contact's transient (stiff wall; NaN without a contact held in the hold window)
  double impact_peak_n = kNone;       ///< largest |f_ext| from the operator's start to the hold window's end
  double overshoot_fraction = kNone;  ///< impact_peak_n over the hold window's mean |f_ext|, less 1
  /// From when (s after the operator began) |f_ext| stays within kSettleBand of the hold
  /// window's mean until the window ends.
  double settle_time_s = kNone;
};

/// A hold window's mean contact force below this [N] is no contact: no transient is measured.
inline constexpr double kContactForceN = 1.0;
/// The settling band, a fraction of the held force.
inline constexpr double kSettleBand = 0.1;

/// The stability verdict: nullopt when mad_rad could not be computed.
struct Verdict {
  std::optional<bool> stable;
  /// Why not stable (or why unknown); empty when stable.
  std::string why;
};

/// Time zero of a run's windows [s, on the traces' clock]: when the leader's simulated operator
/// began (the first row whose `<prefix>operator_s` runs, less its value: leader.motion_starts),
/// else the leader's first row (a trace without that column).
double operator_start_s(const Trace& leader, const std::string& prefix = "");

/// Computes the metrics. Follower values are interpolated at the leader's times where the two
/// are compared. Throws TraceError naming the file and column when a column is missing or a
/// trace has no rows.
RunMetrics analyse(const Trace& leader, const Trace& follower, const AnalysisConfig& config);

/// stable iff mad_rad <= stable_max_mad_rad, force_mad_n <= stable_max_force_mad_n (when
/// known), saturation_fraction <= stable_max_saturation, safe_hold_fraction <=
/// stable_max_safe_hold and no reflex latched; `why` names every reason.
Verdict judge_stability(const RunMetrics& metrics, const AnalysisConfig& config);

/// The latest flows_matched_s of a valid run: max_flows_matched_s, or settle_s when not given.
inline double flows_matched_limit_s(const AnalysisConfig& config) {
  return config.max_flows_matched_s >= 0 ? config.max_flows_matched_s : config.settle_s;
}

/// Why the run's numbers cannot be trusted (empty: they can): a flow that matched late or never.
std::string invalid_reason(const RunMetrics& metrics, const AnalysisConfig& config);

/// The contact's transient (RunMetrics::impact_peak_n, overshoot_fraction, settle_time_s) from
/// the follower's contact force norm `force_n` at times `t_rel_s` (s after the operator began).
void analyse_contact_transient(const std::vector<double>& t_rel_s, const std::vector<double>& force_n, Window hold,
                               RunMetrics& m);

/// The follower's safety record and when the flows matched, from the columns of one arm
/// (`prefix` "" for a one-arm run, "<arm>_" for an arm of a group) into `m`.
void analyse_run_health(const Trace& leader, const Trace& follower, const std::string& prefix, RunMetrics& m);

}  // namespace teleop::experiment
