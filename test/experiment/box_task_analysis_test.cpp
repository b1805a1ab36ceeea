// The box task's run metrics on synthetic two-arm traces whose answers are known: the columns
// land in the right fields, each arm counts, and the table shows the task's metrics.
#include "box_task_analysis.h"

#include <gtest/gtest.h>

#include <teleop/msg/status.h>

#include <cmath>
#include <functional>

#include "teleop/experiment/experiment_runner.h"
#include "teleop/experiment/results_table.h"

namespace teleop::experiment {
namespace {

constexpr double kDt = 0.01;
constexpr size_t kRows = 500;  // 5 s

using Signal = std::function<double(double t_s)>;

Trace make_trace(const std::string& file, const std::vector<std::pair<std::string, Signal>>& columns) {
  Trace trace;
  trace.file = file;
  for (size_t i = 0; i < kRows; ++i) trace.t_s.push_back(50.0 + static_cast<double>(i) * kDt);
  for (const auto& [name, f] : columns) {
    trace.names.push_back(name);
    trace.columns.emplace_back();
    for (double t : trace.t_s) trace.columns.back().push_back(f(t - 50.0));
  }
  return trace;
}

Signal constant(double v) {
  return [v](double) { return v; };
}
bool carried(double t) { return t >= 1.0 && t < 3.0; }

// the box rests in its socket for 1 s, is carried for 2 s (left squeeze 10-14 N, right 12-13 N,
// slipping 3 mm down between the hands) and rests on the shelf floor to the end
Trace follower_trace(double right_torque_ratio = 0.5) {
  auto along = [](double from, double to) {
    return [from, to](double t) { return t < 1.0 ? from : (t >= 3.0 ? to : from + (to - from) * (t - 1.0) / 2.0); };
  };
  std::vector<std::pair<std::string, Signal>> columns{
      {"box_x", along(0.35, 0.60)},
      {"box_y", constant(0.0)},
      {"box_z", [](double t) { return t < 1.0 ? 0.80 : (t >= 3.0 ? 0.89 : 0.80 + 0.09 * (t - 1.0) / 2.0 - 0.0015 * (t - 1.0)); }},
      {"left_x", along(0.35, 0.60)},
      {"left_y", constant(0.1)},
      {"left_z", along(0.84, 0.93)},
      {"right_x", along(0.35, 0.60)},
      {"right_y", constant(-0.1)},
      {"right_z", along(0.84, 0.93)},
      {"left_squeeze_n", [](double t) { return carried(t) ? 10.0 + 2.0 * (t - 1.0) : 0.0; }},
      {"right_squeeze_n", [](double t) { return carried(t) ? (t < 2.0 ? 12.0 : 13.0) : 0.0; }},
      {"support_n", [](double t) { return carried(t) ? 0.0 : 9.81; }},
      {"arm_collision_n", [](double t) { return t > 4.0 ? 2.5 : 0.0; }},
  };
  for (const std::string arm : {"left", "right"}) {
    for (int j = 0; j < 7; ++j) {
      // the right arm's first joint shakes by 0.01 rad at 20 Hz: its MAD is the worst
      const bool shakes = arm == "right" && j == 0;
      columns.emplace_back(arm + "_q_" + std::to_string(j),
                           [shakes](double t) { return shakes ? 0.01 * std::sin(2 * M_PI * 20 * t) : 0.1; });
    }
    columns.emplace_back(arm + "_tdpa_w_j", constant(arm == "left" ? 0.2 : 0.05));
    columns.emplace_back(arm + "_torque_ratio", constant(arm == "left" ? 0.1 : right_torque_ratio));
    columns.emplace_back(arm + "_state", [arm](double t) {
      return arm == "left" && t > 4.5 ? msg::STATE_SAFE_HOLD : msg::STATE_RUNNING;
    });
  }
  return make_trace("follower.csv", columns);
}

Trace leader_trace() {
  return make_trace("leader.csv", {{"left_tdpa_w_j", constant(-0.03)}, {"right_tdpa_w_j", constant(0.1)}});
}

AnalysisConfig config() {
  AnalysisConfig c;
  c.kind = AnalysedTask::kBoxTask;
  c.arms = {"left", "right"};
  c.hold = {1.0, 3.0};
  c.shelf = {{0.58, -0.09, 0.885}, {0.62, 0.09, 0.91}};
  return c;
}

TEST(BoxTaskAnalysis, ReadsEachColumnIntoItsFieldOfTheSeries) {
  const box_task::BoxTaskSeries series = box_task_series(follower_trace());
  ASSERT_EQ(series.samples.size(), kRows);
  const box_task::BoxTaskSample& s = series.samples[150];  // t = 1.5 s, carried
  EXPECT_DOUBLE_EQ(s.t_s, 51.5);
  EXPECT_NEAR(s.box_m.x(), 0.35 + 0.25 * 0.25, 1e-12);
  EXPECT_DOUBLE_EQ(s.left_m.y(), 0.1);
  EXPECT_DOUBLE_EQ(s.right_m.y(), -0.1);
  EXPECT_DOUBLE_EQ(s.left_squeeze_n, 11.0);
  EXPECT_DOUBLE_EQ(s.right_squeeze_n, 12.0);
  EXPECT_DOUBLE_EQ(s.support_n, 0.0);
  EXPECT_DOUBLE_EQ(series.samples[450].arm_collision_n, 2.5);
}

TEST(BoxTaskAnalysis, GivesTheTasksMetricsOfATraceThatPlacesTheBox) {
  const auto m = box_task::evaluate_box_task(box_task_series(follower_trace()), config().shelf);
  EXPECT_TRUE(m.success);
  EXPECT_NEAR(m.task_time_s, 3.0, 1e-9) << "placed at 3 s after the first sample";
  EXPECT_NEAR(m.squeeze_variation_n[0], 4.0, 0.05);
  EXPECT_NEAR(m.squeeze_variation_n[1], 1.0, 1e-9);
  EXPECT_NEAR(m.slip_mm, 3.0, 0.1);
  EXPECT_DOUBLE_EQ(m.max_arm_collision_n, 2.5);
}

TEST(BoxTaskAnalysis, TakesTheWorstArmForEachStabilitySignal) {
  const RunMetrics m = analyse_arms(leader_trace(), follower_trace(0.9995), config());
  // MAD of a sine of amplitude a about its 10-sample running mean over one of the seven joints
  EXPECT_GT(m.mad_rad, 1e-4);
  EXPECT_LT(m.mad_rad, 0.01 / 7);
  EXPECT_DOUBLE_EQ(m.tdpa_min_energy_j, -0.03) << "the left leader's";
  EXPECT_DOUBLE_EQ(m.saturation_fraction, 1.0) << "the right follower's";
  EXPECT_NEAR(m.safe_hold_fraction, 0.1, 0.005) << "the left follower's last half second";
  EXPECT_TRUE(std::isnan(m.force_error_n)) << "no stiff-wall metric";
}

TEST(BoxTaskAnalysis, NamesTheFileAndAMissingArmColumn) {
  AnalysisConfig c = config();
  c.arms = {"left", "middle"};
  try {
    analyse_arms(leader_trace(), follower_trace(), c);
    FAIL() << "no error";
  } catch (const TraceError& e) {
    EXPECT_NE(std::string(e.what()).find("follower.csv"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("middle_q_0"), std::string::npos) << e.what();
  }
}

TEST(BoxTaskAnalysis, TableAndCsvShowTheTasksMetrics) {
  RunRow row;
  row.run = "pfc_tdpa";
  row.profile = "wan-35ms";
  row.status = "ok";
  row.trace_dir = "/tmp/x";
  row.seed = 7;
  row.metrics = analyse_arms(leader_trace(), follower_trace(), config());
  row.box_task = box_task::evaluate_box_task(box_task_series(follower_trace()), config().shelf);
  const std::string table = format_table({row}, "box_task", AnalysedTask::kBoxTask);
  EXPECT_NE(table.find("success"), std::string::npos) << table;
  EXPECT_NE(table.find("slip_mm"), std::string::npos) << table;
  EXPECT_EQ(table.find("f_err_N"), std::string::npos) << "no stiff-wall column\n" << table;
  const std::string csv = format_csv({row}, AnalysedTask::kBoxTask);
  const std::string header = csv.substr(0, csv.find('\n'));
  EXPECT_EQ(header,
            "run,profile,repeat,seed,status,stable,stable_why,success,task_time_s,carry_time_s,squeeze_variation_left_n,"
            "squeeze_variation_right_n,squeeze_min_left_n,squeeze_min_right_n,slip_mm,dropped,max_arm_collision_n,"
            "mad_rad,tdpa_min_energy_j,saturation_fraction,safe_hold_fraction,reflex_latches,flows_matched_s,trace_dir,"
            "note");
  EXPECT_EQ(csv.substr(header.size() + 1, 32), "pfc_tdpa,wan-35ms,1,7,ok,,,yes,3") << csv;
}

}  // namespace
}  // namespace teleop::experiment
