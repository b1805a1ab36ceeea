#include "teleop/experiment/analysis.h"

#include <teleop/msg/status.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

namespace teleop::experiment {
namespace {

// the three columns <prefix>x, <prefix>y, <prefix>z
Axes axes(const Trace& trace, const std::string& prefix) {
  return {trace.column(prefix + "x"), trace.column(prefix + "y"), trace.column(prefix + "z")};
}

Axes interpolate_axes(const Trace& from, const Axes& values, const std::vector<double>& at) {
  return {interpolate(from.t_s, values[0], at), interpolate(from.t_s, values[1], at),
          interpolate(from.t_s, values[2], at)};
}

std::string format(const char* fmt, double a, double b) {
  char text[96];
  std::snprintf(text, sizeof text, fmt, a, b);
  return text;
}

// what tripped the follower's reflex, as its trace's `reflex` column counts it (follower's
// ReflexCause, follower/include/teleop/follower/safety_reflex.h)
const char* reflex_cause_name(double cause) {
  switch (static_cast<int>(cause)) {
    case 1: return "joint torque";
    case 2: return "force";
    case 3: return "moment";
    case 4: return "joint speed";
    default: return "unknown";
  }
}

}  // namespace

double operator_start_s(const Trace& leader, const std::string& prefix) {
  if (!leader.has(prefix + "operator_s")) return leader.t_s.front();
  const std::vector<double>& clock = leader.column(prefix + "operator_s");
  for (size_t i = 0; i < clock.size(); ++i) {
    if (clock[i] > 0) return leader.t_s[i] - clock[i];
  }
  return leader.t_s.front();
}

RunMetrics analyse(const Trace& leader, const Trace& follower, const AnalysisConfig& config) {
  require_rows(leader);
  require_rows(follower);
  const double t0_s = operator_start_s(leader);
  const std::vector<double> t_leader = relative(leader.t_s, t0_s);
  const std::vector<double> t_follower = relative(follower.t_s, t0_s);
  const Window hold = config.hold;
  const Window after_settle{config.settle_s, std::numeric_limits<double>::infinity()};

  // leader and follower compared at the leader's times
  const Axes x_cmd = axes(leader, "x_cmd_");
  const Axes f_felt = axes(leader, "f_felt_");
  const Axes x_follower = axes(follower, "x_");
  const Axes x_at_leader = interpolate_axes(follower, x_follower, leader.t_s);
  const Axes f_ext_at_leader = interpolate_axes(follower, axes(follower, "f_ext_"), leader.t_s);
  const std::vector<double> force_error = distance(f_felt, f_ext_at_leader);
  const std::vector<double> tracking_error = distance(x_cmd, x_at_leader);

  RunMetrics m;
  m.force_error_n = mean_in(t_leader, force_error, hold);
  m.force_felt_n = mean_in(t_leader, norm(f_felt), hold);
  m.force_exerted_n = mean_in(t_leader, norm(f_ext_at_leader), hold);
  m.tracking_rmse_m = rms_in(t_leader, tracking_error, after_settle);
  m.tracking_hold_m = rms_in(t_leader, tracking_error, hold);

  // the follower's own signals at its own times
  double mad_sum = 0;
  const auto joints = follower.numbered("q_");
  for (const auto* q : joints) mad_sum += mean_absolute_deviation_in(t_follower, *q, kMadWindowSamples, hold);
  m.mad_rad = mad_sum / static_cast<double>(joints.size());
  const std::vector<double> contact_force = norm(axes(follower, "f_ext_"));
  m.force_mad_n = mean_absolute_deviation_in(t_follower, contact_force, kMadWindowSamples, hold);
  analyse_contact_transient(t_follower, contact_force, hold, m);
  double ptp_squared = 0;
  for (const auto& axis : x_follower) ptp_squared += std::pow(peak_to_peak_in(t_follower, axis, hold), 2);
  m.hold_ptp_m = std::sqrt(ptp_squared);
  m.tdpa_min_energy_j = std::fmin(min_finite(leader.column("tdpa_w_j")), min_finite(follower.column("tdpa_w_j")));
  m.saturation_fraction = fraction_at_least(follower.column("torque_ratio"), kSaturatedTorqueRatio);
  m.safe_hold_fraction = fraction_equal(follower.column("state"), static_cast<double>(msg::STATE_SAFE_HOLD));
  analyse_run_health(leader, follower, "", m);
  return m;
}

Verdict judge_stability(const RunMetrics& m, const AnalysisConfig& config) {
  if (std::isnan(m.mad_rad)) return {std::nullopt, "no follower joint samples in the hold window"};
  std::string why;
  if (!(m.mad_rad <= config.stable_max_mad_rad)) {
    why = format("MAD %.3g rad > %.3g", m.mad_rad, config.stable_max_mad_rad);
  }
  if (m.force_mad_n > config.stable_max_force_mad_n) {
    why += (why.empty() ? "" : "; ") +
           format("contact force MAD %.3g N > %.3g", m.force_mad_n, config.stable_max_force_mad_n);
  }
  if (m.saturation_fraction > config.stable_max_saturation) {
    why += (why.empty() ? "" : "; ") +
           format("saturated %.3g of the time > %.3g", m.saturation_fraction, config.stable_max_saturation);
  }
  if (m.safe_hold_fraction > config.stable_max_safe_hold) {
    why += (why.empty() ? "" : "; ") +
           format("in safe hold %.3g of the time > %.3g", m.safe_hold_fraction, config.stable_max_safe_hold);
  }
  if (m.reflex_latches > 0) {
    why += std::string(why.empty() ? "" : "; ") + "safety reflex latched " +
           std::to_string(std::lround(m.reflex_latches)) + " times (first: " + reflex_cause_name(m.reflex_cause) + ")";
  }
  return {why.empty(), why};
}

}  // namespace teleop::experiment
