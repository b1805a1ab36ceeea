// The run metrics on synthetic leader/follower traces whose answers are known.
#include "teleop/experiment/analysis.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <teleop/msg/status.h>

#include <cmath>
#include <complex>
#include <functional>
#include <numbers>

#include "test_helpers.h"

namespace teleop::experiment {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
using Signal = std::function<double(size_t row, double t_rel)>;

// a trace of `rows` rows at `dt` starting `start_rel` after the leader's first row (t0 = 100 s)
Trace make_trace(const std::string& file, size_t rows, double dt, double start_rel,
                 const std::vector<std::pair<std::string, Signal>>& columns) {
  Trace t;
  t.file = file;
  for (size_t i = 0; i < rows; ++i) t.t_s.push_back(100.0 + start_rel + static_cast<double>(i) * dt);
  for (const auto& [name, f] : columns) {
    t.names.push_back(name);
    t.columns.emplace_back();
    for (size_t i = 0; i < rows; ++i) t.columns.back().push_back(f(i, t.t_s[i] - 100.0));
  }
  return t;
}

Signal constant(double v) {
  return [v](size_t, double) { return v; };
}
bool in_hold(double t_rel) { return t_rel >= 6.0 && t_rel <= 10.0; }

constexpr double kShakeRad = 0.01;
constexpr double kShakeHz = 20.0;

Trace leader_trace(double duration_s = 11.0) {
  return make_trace("leader.csv", static_cast<size_t>(duration_s * 1000), 1e-3, 0.0,
                    {{"x_cmd_x", constant(0.5)},
                     {"x_cmd_y", [](size_t, double t) { return 0.01 * t; }},
                     {"x_cmd_z", constant(0.2)},
                     {"f_felt_x", constant(0)},
                     {"f_felt_y", constant(0)},
                     {"f_felt_z", [](size_t, double t) { return in_hold(t) ? 10.0 : 0.0; }},
                     {"tdpa_w_j", constant(kNaN)},
                     {"state", constant(msg::STATE_RUNNING)}});
}

// 1 kHz too, but on its own clock phase (0.4 ms later) and starting earlier, ending later
Trace follower_trace(const std::vector<std::string>& drop = {}, double duration_s = 11.4) {
  std::vector<std::pair<std::string, Signal>> columns{
      {"x_x", constant(0.5 + 0.003)},
      {"x_y", [](size_t, double t) { return 0.01 * t; }},
      {"x_z", constant(0.2 - 0.004)},
      {"f_ext_x", constant(0)},
      {"f_ext_y", constant(6)},
      {"f_ext_z", constant(18)},
      {"q_0", [](size_t, double t) { return kShakeRad * std::sin(2 * std::numbers::pi * kShakeHz * t); }},
      {"tdpa_w_j", [](size_t i, double) { return i == 777 ? -0.5 : 0.25; }},
      {"torque_ratio", [](size_t i, double) { return i % 50 == 0 ? 1.0 : 0.3; }},
      {"state", [](size_t i, double) { return i % 10 == 0 ? msg::STATE_SAFE_HOLD : msg::STATE_RUNNING; }}};
  for (int j = 1; j < 7; ++j) columns.push_back({"q_" + std::to_string(j), constant(0.1 * j)});
  std::erase_if(columns, [&](const auto& c) { return std::find(drop.begin(), drop.end(), c.first) != drop.end(); });
  return make_trace("follower.csv", static_cast<size_t>(duration_s * 1000), 1e-3, -0.2996, columns);
}

TEST(Analyse, GivesKnownForceErrorsFromConstantForcesInTheHoldWindowOnly) {
  const RunMetrics m = analyse(leader_trace(), follower_trace(), AnalysisConfig{});
  // felt (0, 0, 10) in the hold window, exerted (0, 6, 18): difference (0, -6, -8)
  EXPECT_NEAR(m.force_error_n, 10.0, 1e-9);
  EXPECT_NEAR(m.force_felt_n, 10.0, 1e-9);
  EXPECT_NEAR(m.force_exerted_n, std::sqrt(36.0 + 324.0), 1e-9);
}

TEST(Analyse, GivesTheConstantOffsetAsTrackingErrorAcrossUnequalSampleTimes) {
  const RunMetrics m = analyse(leader_trace(), follower_trace(), AnalysisConfig{});
  // x_y moves in both, sampled at different times: interpolation makes it cancel exactly
  EXPECT_NEAR(m.tracking_rmse_m, 0.005, 1e-12);
  EXPECT_NEAR(m.tracking_hold_m, 0.005, 1e-12);
}

TEST(Analyse, AveragesTheJointMadOverJointsAndMeasuresThePeakToPeak) {
  const RunMetrics m = analyse(leader_trace(), follower_trace(), AnalysisConfig{});
  // q_0 shakes (closed form as in MeanAbsoluteDeviation.MatchesTheClosedFormForASine), q_1..q_6 hold still
  const double w = 2 * std::numbers::pi * kShakeHz;
  const double dt = 1e-3;
  const double g = std::sin(5 * w * dt) / (10 * std::sin(w * dt / 2));
  const double sine_mad = 2 / std::numbers::pi * kShakeRad * std::abs(1.0 - g * std::polar(1.0, -w * dt / 2));
  EXPECT_NEAR(m.mad_rad, sine_mad / 7, 2e-3 * sine_mad / 7);
  // x_y climbs 0.01 m/s for the 4 s of the window; x and z stand still
  EXPECT_NEAR(m.hold_ptp_m, 0.04, 2e-5);
}

TEST(Analyse, CountsSaturationAndSafeHoldRowsAndFindsTheLowestTdpaEnergy) {
  const RunMetrics m = analyse(leader_trace(), follower_trace(), AnalysisConfig{});
  EXPECT_DOUBLE_EQ(m.saturation_fraction, 0.02);
  EXPECT_DOUBLE_EQ(m.safe_hold_fraction, 0.1);
  EXPECT_DOUBLE_EQ(m.tdpa_min_energy_j, -0.5);  // the leader's are all NaN (no TDPA there)
}

TEST(Analyse, ReportsNoTdpaEnergyWhenBothTracesAreAllNan) {
  Trace follower = follower_trace();
  for (double& w : follower.columns[7]) w = kNaN;
  ASSERT_EQ(follower.names[7], "tdpa_w_j");
  EXPECT_TRUE(std::isnan(analyse(leader_trace(), follower, AnalysisConfig{}).tdpa_min_energy_j));
}

TEST(Analyse, NamesTheFileAndColumnWhenAColumnIsMissing) {
  EXPECT_EQ(test::error_of<TraceError>([] { analyse(leader_trace(), follower_trace({"f_ext_y"}), AnalysisConfig{}); }),
            "follower.csv: no column 'f_ext_y'");
  EXPECT_EQ(test::error_of<TraceError>([] { analyse(leader_trace(), follower_trace({"q_0"}), AnalysisConfig{}); }),
            "follower.csv: no column 'q_0'");
  Trace empty = leader_trace();
  empty.t_s.clear();
  EXPECT_EQ(test::error_of<TraceError>([&] { analyse(empty, follower_trace(), AnalysisConfig{}); }),
            "leader.csv: the trace has no rows");
}

TEST(JudgeStability, SaysWhyNotWhenMadAndSaturationExceedTheLimits) {
  AnalysisConfig config;
  const RunMetrics m = analyse(leader_trace(), follower_trace(), config);
  config.stable_max_mad_rad = m.mad_rad / 2;
  const Verdict v = judge_stability(m, config);
  ASSERT_TRUE(v.stable.has_value());
  EXPECT_FALSE(*v.stable);
  EXPECT_NE(v.why.find("MAD"), std::string::npos) << v.why;
  EXPECT_NE(v.why.find("saturated 0.02 of the time > 0.01"), std::string::npos) << v.why;
}

TEST(JudgeStability, ContactForceChatterIsUnstableEvenWithQuietJoints) {
  // the wall holds the joints still while the contact is made and lost every other cycle: |f_ext|
  // alternates 4 N and 12 N, whose MAD from a 10-sample running mean is exactly 4 N
  Trace follower = follower_trace();
  const auto column = [&](const char* name) -> std::vector<double>& {
    return follower.columns[static_cast<size_t>(std::find(follower.names.begin(), follower.names.end(), name) -
                                                follower.names.begin())];
  };
  auto& f = column("f_ext_x");
  for (size_t i = 0; i < f.size(); ++i) f[i] = i % 2 == 0 ? -4.0 : -12.0;
  std::fill(column("f_ext_y").begin(), column("f_ext_y").end(), 0.0);
  std::fill(column("f_ext_z").begin(), column("f_ext_z").end(), 0.0);
  AnalysisConfig config;
  config.stable_max_mad_rad = 1.0;
  config.stable_max_saturation = 0.05;
  const RunMetrics m = analyse(leader_trace(), follower, config);
  EXPECT_NEAR(m.force_mad_n, 4.0, 1e-9);
  const Verdict v = judge_stability(m, config);
  EXPECT_EQ(v.stable, std::optional<bool>(false));
  EXPECT_NE(v.why.find("contact force MAD 4 N > 0.1"), std::string::npos) << v.why;
}

TEST(JudgeStability, IsStableWithinTheLimitsAndUnknownWithoutHoldSamples) {
  AnalysisConfig config;
  config.stable_max_mad_rad = 1.0;
  config.stable_max_saturation = 0.05;
  config.stable_max_safe_hold = 0.2;  // the trace holds every 10th row
  const Verdict v = judge_stability(analyse(leader_trace(), follower_trace(), config), config);
  EXPECT_EQ(v.stable, std::optional<bool>(true));
  EXPECT_TRUE(v.why.empty());
  // a 3 s run never reaches the hold window [6, 10]
  const RunMetrics short_run = analyse(leader_trace(3.0), follower_trace({}, 3.0), config);
  EXPECT_TRUE(std::isnan(short_run.mad_rad));
  EXPECT_FALSE(judge_stability(short_run, config).stable.has_value());
}

// `trace` with the column `name` (added, or replaced) holding `f`
Trace with_column(Trace trace, const std::string& name, const Signal& f) {
  auto it = std::find(trace.names.begin(), trace.names.end(), name);
  if (it == trace.names.end()) {
    trace.names.push_back(name);
    trace.columns.emplace_back(trace.t_s.size());
    it = trace.names.end() - 1;
  }
  auto& column = trace.columns[static_cast<size_t>(it - trace.names.begin())];
  for (size_t i = 0; i < column.size(); ++i) column[i] = f(i, trace.t_s[i] - 100.0);
  return trace;
}

// 0 before `from_s` (after the leader's first row), `value` after
Signal from(double from_s, double value) {
  return [from_s, value](size_t, double t) { return t >= from_s ? value : 0.0; };
}

TEST(JudgeStability, EveryLatchedReflexAndALongHoldAreReasons) {
  AnalysisConfig config;
  config.stable_max_mad_rad = 1.0;
  config.stable_max_saturation = 0.05;
  // the speed reflex (4) latched from 3 s to 4 s, the force reflex (2) from 7 s to 8 s
  const Trace follower = with_column(follower_trace(), "reflex", [](size_t, double t) {
    return t >= 3.0 && t < 4.0 ? 4.0 : t >= 7.0 && t < 8.0 ? 2.0 : 0.0;
  });
  const RunMetrics m = analyse(leader_trace(), follower, config);
  EXPECT_EQ(m.reflex_latches, 2.0);
  EXPECT_EQ(m.reflex_cause, 4.0);
  const Verdict v = judge_stability(m, config);
  EXPECT_EQ(v.stable, std::optional<bool>(false));
  EXPECT_NE(v.why.find("in safe hold 0.1 of the time > 0.05"), std::string::npos) << v.why;
  EXPECT_NE(v.why.find("safety reflex latched 2 times (first: joint speed)"), std::string::npos) << v.why;
  // without the column (an older trace) nothing is counted
  EXPECT_TRUE(std::isnan(analyse(leader_trace(), follower_trace(), config).reflex_latches));
}

TEST(Analyse, CountsTimeFromWhenTheOperatorBegan) {
  // the operator waited 0.7 s for the leader to be in command (leader.motion_starts: in_command)
  const Trace waited = with_column(leader_trace(), "operator_s", [](size_t, double t) { return t > 0.7 ? t - 0.7 : 0.0; });
  EXPECT_NEAR(operator_start_s(waited), 100.7, 1e-9);
  EXPECT_EQ(operator_start_s(leader_trace()), 100.0) << "without the column: the first row";
  // the hold window [6, 10] s after it: the felt 10 N of [6, 10] s after the first row cover 3.3 of its 4 s
  EXPECT_NEAR(analyse(waited, follower_trace(), AnalysisConfig{}).force_felt_n, 10.0 * 3.3 / 4.0, 0.01);
}

TEST(Analyse, MeasuresTheContactsPeakOvershootAndSettlingTime) {
  // contact at 1 s with 18 N, 12 N from 1.5 s (outside 10 % of the held 10 N), 10 N from 2 s on
  Trace follower = with_column(follower_trace(), "f_ext_x", [](size_t, double t) {
    return t < 1.0 ? 0.0 : t < 1.5 ? 18.0 : t < 2.0 ? 12.0 : 10.0;
  });
  follower = with_column(with_column(follower, "f_ext_y", constant(0)), "f_ext_z", constant(0));
  const RunMetrics m = analyse(leader_trace(), follower, AnalysisConfig{});
  EXPECT_NEAR(m.impact_peak_n, 18.0, 1e-9);
  EXPECT_NEAR(m.overshoot_fraction, 0.8, 1e-9);
  EXPECT_NEAR(m.settle_time_s, 2.0, 2e-3);
  // a bounce late in the hold window: settled only after it; one at the window's end: never
  const Trace late = with_column(follower, "f_ext_x", [](size_t, double t) { return t > 9.0 && t < 9.1 ? 3.0 : 10.0; });
  EXPECT_NEAR(analyse(leader_trace(), late, AnalysisConfig{}).settle_time_s, 9.1, 2e-3);
  const Trace bouncing = with_column(follower, "f_ext_x", [](size_t, double t) { return t > 9.95 ? 3.0 : 10.0; });
  EXPECT_TRUE(std::isinf(analyse(leader_trace(), bouncing, AnalysisConfig{}).settle_time_s));
  // no contact held: no transient
  const Trace free = with_column(follower, "f_ext_x", constant(0.2));
  EXPECT_TRUE(std::isnan(analyse(leader_trace(), free, AnalysisConfig{}).impact_peak_n));
}

TEST(RunHealth, EachArmsLatchesCountAndTheFirstArmThatLatchedNamesTheCause) {
  Trace follower = with_column(follower_trace(), "left_reflex", from(3.0, 4.0));  // joint speed
  follower = with_column(follower, "right_reflex", from(5.0, 2.0));              // force
  RunMetrics m;
  analyse_run_health(leader_trace(), follower, "left_", m);
  analyse_run_health(leader_trace(), follower, "right_", m);
  EXPECT_EQ(m.reflex_latches, 2.0);
  EXPECT_EQ(m.reflex_cause, 4.0);
  RunMetrics only_right;
  analyse_run_health(leader_trace(), with_column(follower, "left_reflex", constant(0)), "left_", only_right);
  analyse_run_health(leader_trace(), follower, "right_", only_right);
  EXPECT_EQ(only_right.reflex_latches, 1.0);
  EXPECT_EQ(only_right.reflex_cause, 2.0);
}

TEST(RunHealth, TheFlowsMatchWhenTheLeaderIsInCommandAndTheFollowerFollowsItsFirstCommand) {
  const Trace leader = with_column(leader_trace(), "state", [](size_t, double t) {
    return t >= 0.5 ? msg::STATE_RUNNING : msg::STATE_STARTING;
  });
  const AnalysisConfig config;  // settle_s 1.0: the limit
  const RunMetrics in_time = analyse(leader, with_column(follower_trace(), "cmd_session", from(0.3, 1)), config);
  EXPECT_NEAR(in_time.flows_matched_s, 0.5, 1e-9);
  EXPECT_EQ(invalid_reason(in_time, config), "");

  // the follower matched its commands 4 s late (discovery): the run's numbers are no result
  const RunMetrics late = analyse(leader, with_column(follower_trace(), "cmd_session", from(4.0, 1)), config);
  EXPECT_NEAR(late.flows_matched_s, 4.0, 2e-3);
  EXPECT_NE(invalid_reason(late, config).find("the flows matched 4.00 s after the operator began (limit 1.00 s"),
            std::string::npos)
      << invalid_reason(late, config);
  AnalysisConfig patient = config;
  patient.max_flows_matched_s = 5.0;
  EXPECT_EQ(invalid_reason(late, patient), "");

  const RunMetrics never = analyse(leader, with_column(follower_trace(), "cmd_session", constant(0)), config);
  EXPECT_TRUE(std::isinf(never.flows_matched_s));
  EXPECT_NE(invalid_reason(never, config).find("never all matched"), std::string::npos);
  // traces without the columns are not judged
  EXPECT_EQ(invalid_reason(analyse(leader_trace(), follower_trace(), config), config), "");
}

}  // namespace
}  // namespace teleop::experiment
