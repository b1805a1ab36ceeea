// The architectures end to end (issue 6): the stiff-wall experiment with the real leader,
// follower and twin processes under the seeded 35 ms round-trip profile, one architecture per
// test, each held to the bounds it is expected to meet (docs/architectures.md); and the safety
// case of the follower dying while the operator pushes it into the wall.

#include <gtest/gtest.h>
#include <signal.h>

#include <teleop/msg/status.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <thread>

#include "process_helpers.h"
#include "results_row.h"
#include "teleop/common/clock.h"
#include "teleop/experiment/trace.h"

namespace teleop::test {
namespace {

// one row of the experiment's CSV, by column name; `report_dir` (if given) gets where the traces are
ResultsRow run_stiff_wall(const std::string& architecture, const std::string& experiment = "stiff_wall.yaml",
                          std::string* report_dir = nullptr, const std::string& profile = "wan-35ms") {
  const std::string dir = make_temp_dir();
  if (report_dir != nullptr) *report_dir = dir + "/" + architecture + "/" + profile;
  const std::string csv = dir + "/results.csv";
  const ProcessResult r = run_process({bin("teleop"), "experiment", source("config/experiments/" + experiment), "--runs",
                                       architecture, "--profiles", profile, "--report-dir", dir, "--csv", csv,
                                       "--domain", std::to_string(unique_domain()), "--no-plots"},
                                      std::chrono::seconds(90));
  EXPECT_EQ(r.exit_status, 0) << r.output;
  const ResultsRow values = read_results_row(csv);
  ::testing::Test::RecordProperty("row", read_file(csv));
  return values;
}

TEST(StiffWall, PositionPositionIsStableAndRendersTheContactForce) {
  const auto row = run_stiff_wall("position_position");
  ASSERT_EQ(row.at("status"), "ok");
  EXPECT_EQ(row.at("stable"), "yes") << row.at("stable_why");
  EXPECT_GT(number(row, "force_exerted_n"), 5.0) << "the follower presses on the wall";
  EXPECT_LT(number(row, "force_error_n"), 1.0);
  EXPECT_LT(number(row, "tracking_hold_m"), 0.01);
}

TEST(StiffWall, PfcWithoutPassivityIsDetectedUnstable) {
  const auto row = run_stiff_wall("pfc");
  ASSERT_EQ(row.at("status"), "ok");
  // the observers (observe only) see the channel generate energy, and the verdict says unstable
  EXPECT_LT(number(row, "tdpa_min_energy_j"), -0.05);
  EXPECT_EQ(row.at("stable"), "no");
}

TEST(StiffWall, PfcWithTdpaStaysPassiveAndStable) {
  const auto row = run_stiff_wall("pfc_tdpa");
  ASSERT_EQ(row.at("status"), "ok");
  EXPECT_EQ(row.at("stable"), "yes") << row.at("stable_why");
  EXPECT_GE(number(row, "tdpa_min_energy_j"), -1e-9) << "the passivity observers never go negative";
  // what the operator feels is what the follower exerts; how hard it presses is not asserted:
  // that depends on the position drift the dampers leave, which grows when the loops run late
  // (the slower ASan build left the follower barely touching the wall, docs/architectures.md)
  EXPECT_LT(number(row, "force_error_n"), 1.0);
  EXPECT_LT(number(row, "tracking_hold_m"), 0.02);
}

// the operator's device a plugin (the reference one: a simulated 3-DoF delta held by a simulated
// hand, docs/devices/plugins.md): it drives the follower into the wall and is rendered the force
// the follower exerts, on the LAN (under 35 ms its light handle chatters on the wall: the
// experiment's table, docs/architectures.md)
TEST(StiffWall, ADeltaPluginPressesTheWallAndFeelsWhatTheFollowerExerts) {
  const auto row = run_stiff_wall("pfc_tdpa_delta", "stiff_wall.yaml", nullptr, "lan");
  ASSERT_EQ(row.at("status"), "ok");
  EXPECT_EQ(row.at("stable"), "yes") << row.at("stable_why");
  EXPECT_GE(number(row, "tdpa_min_energy_j"), -1e-9);
  EXPECT_GT(number(row, "force_exerted_n"), 3.0) << "the follower presses on the wall";
  EXPECT_LT(number(row, "force_error_n"), 1.0) << "the delta is rendered what the follower exerts";
}

TEST(StiffWall, ModelMediatedIsStableAndPressesLikeTheTwin) {
  const auto row = run_stiff_wall("mmt");
  ASSERT_EQ(row.at("status"), "ok");
  EXPECT_EQ(row.at("stable"), "yes") << row.at("stable_why");
  EXPECT_GT(number(row, "force_exerted_n"), 5.0);
  // 1.3 N in the normal build; 4.8 N once in the ASan build under load: the follower's joint
  // friction holds more of the late loops' push (docs/architectures.md)
  EXPECT_LT(number(row, "force_error_n"), 6.0);
  EXPECT_LT(number(row, "tracking_hold_m"), 0.01);
}

// MMT with the twin's wall 2 cm off the real one (config/experiments/stiff_wall_model_error.yaml):
// the follower's measurements move the twin's wall to where the real one is, no faster than the
// rate limit, and the operator then feels what the follower exerts (docs/architectures.md).
void expect_corrected_to(const std::string& run, double true_offset_m) {
  std::string dir;
  const auto row = run_stiff_wall(run, "stiff_wall_model_error.yaml", &dir);
  ASSERT_EQ(row.at("status"), "ok");
  EXPECT_EQ(row.at("stable"), "yes") << row.at("stable_why");
  EXPECT_GT(number(row, "force_exerted_n"), 5.0);
  // uncorrected: 28 N (near) and 64 N (far). What is left is the follower's static joint friction
  // holding part of the commanded torque, as with the exact model: corrected 1.0-2.9 N in the
  // normal build (exact model 1.3 N), up to 6.4 N in the ASan build under load (exact model 4.8 N)
  EXPECT_LT(number(row, "force_error_n"), 10.0);
  const experiment::Trace twin = experiment::read_trace(dir + "/twin.csv");
  const auto& offset = twin.column("env_offset_m");
  ASSERT_GT(offset.size(), 5000u);
  double largest_step = 0.0, worst_in_hold = 0.0;
  for (size_t k = 1; k < offset.size(); ++k) {
    largest_step = std::max(largest_step, std::abs(offset[k] - offset[k - 1]));
    // the hold window of the analysis starts 5 s after the leader's first row
    if (twin.t_s[k] - twin.t_s[0] > 5.0) worst_in_hold = std::max(worst_in_hold, std::abs(offset[k] - true_offset_m));
  }
  ::testing::Test::RecordProperty("final_offset_m", std::to_string(offset.back()));
  EXPECT_LT(worst_in_hold, 0.003) << "within 3 mm of the truth in the hold window";
  // rate_m_per_s 0.02 at 1 kHz: 20 um per cycle (a late cycle may catch up one more)
  EXPECT_LE(largest_step, 2 * 2e-5 + 1e-8);
}

TEST(StiffWall, ModelMediatedCorrectsATwinWallBehindTheRealOne) {
  // the twin's wall 2 cm further away (+x): it must come 2 cm towards the robot (n = -x)
  expect_corrected_to("mmt_wall_far_corrected", 0.02);
}

TEST(StiffWall, ModelMediatedCorrectsATwinWallInFrontOfTheRealOne) {
  expect_corrected_to("mmt_wall_near_corrected", -0.02);
}

// The follower is SIGKILLed while the operator pushes it into the wall (position-position, the
// contact force felt): the leader's feedback fades to zero, never stepping above its rate limit.
TEST(StiffWall, FollowerKilledInContactFadesTheFeedbackOut) {
  const std::string dir = make_temp_dir();
  const std::string domain = std::to_string(unique_domain());
  const std::string follower_config = config_copy(dir, "follower.yaml", {});
  const std::string leader_config = config_copy(dir, "leader_stiff_wall.yaml", {});
  RunningProcess follower({bin("teleop_follower"), "-c", follower_config, "--domain", domain, "-d", "20"});
  RunningProcess leader({bin("teleop_leader"), "-c", leader_config, "--domain", domain, "-d", "6", "--trace",
                         dir + "/leader.csv"});
  std::this_thread::sleep_for(std::chrono::milliseconds(4500));  // pushed in by 2 s, held since
  const double killed_s = static_cast<double>(monotonic_now_ns()) * 1e-9;
  follower.process().signal(SIGKILL);
  EXPECT_EQ(leader.stop(0, std::chrono::seconds(15)), 0) << leader.output();

  const experiment::Trace trace = experiment::read_trace(dir + "/leader.csv");
  const auto& t = trace.t_s;
  const auto& state = trace.column("state");
  const auto torques = trace.numbered("tau_fb_");
  ASSERT_EQ(torques.size(), 7u);
  double felt_before = 0.0, largest_step = 0.0, zero_at = std::nan(""), lost_at = std::nan("");
  size_t lost_row = 0, zero_row = 0;  // a row per executed cycle
  for (size_t k = 1; k < t.size(); ++k) {
    double norm = 0.0;
    for (const auto* tau : torques) {
      largest_step = std::max(largest_step, std::abs((*tau)[k] - (*tau)[k - 1]));
      norm += (*tau)[k] * (*tau)[k];
    }
    if (t[k] < killed_s) felt_before = std::sqrt(norm);
    if (t[k] > killed_s && std::isnan(lost_at) && state[k] == static_cast<double>(msg::STATE_SAFE_HOLD)) {
      lost_at = t[k];
      lost_row = k;
    }
    if (t[k] > killed_s && std::isnan(zero_at) && norm == 0.0) {
      zero_at = t[k];
      zero_row = k;
    }
  }
  RecordProperty("felt_before_nm", std::to_string(felt_before));
  EXPECT_GT(felt_before, 1.0) << "the operator felt the contact";
  ASSERT_FALSE(std::isnan(lost_at)) << "the leader reported the follower lost";
  ASSERT_FALSE(std::isnan(zero_at)) << "the feedback faded to zero";
  // stated: lost within peer_timeout_ms (100) or the liveliness lease (250), faded in fade_ms (200)
  // of the leader's cycles: counted in executed cycles (trace rows), since a loaded host skips
  // deadlines and stretches the fade in wall time (measured: 0.37 s while builds ran)
  EXPECT_LT(lost_at - killed_s, 0.25 + 0.05);
  EXPECT_LE(zero_row - lost_row, 200u + 10u) << "faded in " << zero_at - lost_at << " s";
  // max_rate_nm_per_s 500 at 1 kHz: 0.5 Nm per cycle (the trace keeps 9 significant digits)
  EXPECT_LE(largest_step, 0.5 + 1e-6);
}

}  // namespace
}  // namespace teleop::test
