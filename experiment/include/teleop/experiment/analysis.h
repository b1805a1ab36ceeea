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

/// The `analysis:` section of an experiment file. Times are seconds after the first leader row.
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
};

/// The stability verdict: nullopt when mad_rad could not be computed.
struct Verdict {
  std::optional<bool> stable;
  /// Why not stable (or why unknown); empty when stable.
  std::string why;
};

/// Computes the metrics. Follower values are interpolated at the leader's times where the two
/// are compared. Throws TraceError naming the file and column when a column is missing or a
/// trace has no rows.
RunMetrics analyse(const Trace& leader, const Trace& follower, const AnalysisConfig& config);

/// stable iff mad_rad <= stable_max_mad_rad, force_mad_n <= stable_max_force_mad_n (when
/// known) and saturation_fraction <= stable_max_saturation.
Verdict judge_stability(const RunMetrics& metrics, const AnalysisConfig& config);

}  // namespace teleop::experiment
