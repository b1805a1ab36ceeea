#include "box_task_analysis.h"

#include <teleop/msg/status.h>

#include <cmath>

namespace teleop::experiment {
namespace {

double nan_max(double a, double b) { return std::isnan(a) ? b : (std::isnan(b) ? a : std::fmax(a, b)); }

// the arm's joints' MAD from their running mean in `hold`, the mean over its joints
double arm_mad_rad(const Trace& follower, const std::vector<double>& t_s, const std::string& arm, Window hold) {
  double sum = 0;
  const auto joints = follower.numbered(arm + "_q_");
  for (const auto* q : joints) sum += mean_absolute_deviation_in(t_s, *q, kMadWindowSamples, hold);
  return sum / static_cast<double>(joints.size());
}

}  // namespace

box_task::BoxTaskSeries box_task_series(const Trace& follower) {
  std::vector<const std::vector<double>*> columns;
  for (size_t c = 1; c < box_task::kBoxTaskColumns.size(); ++c) columns.push_back(&follower.column(box_task::kBoxTaskColumns[c]));
  box_task::BoxTaskSeries series;
  series.samples.reserve(follower.t_s.size());
  for (size_t i = 0; i < follower.t_s.size(); ++i) {
    // the columns in the order of BoxTaskSample's fields (kBoxTaskColumns)
    auto v = [&](size_t c) { return (*columns[c])[i]; };
    box_task::BoxTaskSample s;
    s.t_s = follower.t_s[i];
    s.box_m = {v(0), v(1), v(2)};
    s.left_m = {v(3), v(4), v(5)};
    s.right_m = {v(6), v(7), v(8)};
    s.left_squeeze_n = v(9);
    s.right_squeeze_n = v(10);
    s.support_n = v(11);
    s.arm_collision_n = v(12);
    series.append(s);
  }
  return series;
}

RunMetrics analyse_arms(const Trace& leader, const Trace& follower, const AnalysisConfig& config) {
  require_rows(leader);
  require_rows(follower);
  const double t0_s = config.arms.empty() ? leader.t_s.front() : operator_start_s(leader, config.arms.front() + "_");
  const std::vector<double> t_follower = relative(follower.t_s, t0_s);

  RunMetrics m;
  for (const std::string& arm : config.arms) {
    m.mad_rad = nan_max(m.mad_rad, arm_mad_rad(follower, t_follower, arm, config.hold));
    m.tdpa_min_energy_j = std::fmin(m.tdpa_min_energy_j, std::fmin(min_finite(leader.column(arm + "_tdpa_w_j")),
                                                                   min_finite(follower.column(arm + "_tdpa_w_j"))));
    m.saturation_fraction =
        nan_max(m.saturation_fraction, fraction_at_least(follower.column(arm + "_torque_ratio"), kSaturatedTorqueRatio));
    m.safe_hold_fraction = nan_max(m.safe_hold_fraction, fraction_equal(follower.column(arm + "_state"),
                                                                        static_cast<double>(msg::STATE_SAFE_HOLD)));
    analyse_run_health(leader, follower, arm + "_", m);
  }
  return m;
}

}  // namespace teleop::experiment
