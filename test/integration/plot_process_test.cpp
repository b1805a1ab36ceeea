// The figures (docs/plots.md) as real processes: `teleop experiment` draws each run's figures and
// one per metric, `teleop plot` draws a run's again elsewhere; png_check.py opens every PNG and
// checks its size and that its plot area shows data; a recording's topics are exported as CSV and
// drawn. A folder without traces is an error naming it.
#include <gtest/gtest.h>

#include <filesystem>

#include "figure_check.h"
#include "process_helpers.h"
#include "teleop/experiment/plots.h"

namespace teleop::test {
namespace {
namespace fs = std::filesystem;

const std::vector<std::string> kRunFigures = {"position", "force", "tdpa_energy", "lateness", "states"};

std::vector<std::string> pngs(const std::string& dir, const std::string& prefix,
                              const std::vector<std::string>& names) {
  std::vector<std::string> out;
  for (const std::string& n : names) out.push_back(dir + "/" + prefix + n + ".png");
  return out;
}

// 2 s of the stiff wall under PFC+TDPA (so every figure has its columns): the run's five figures
// in its folder, the metrics' beside the CSV; then `teleop plot` of that run into another folder
TEST(PlotProcess, TheExperimentDrawsItsRunsAndMetricsAndPlotDrawsARunAgain) {
  const std::string dir = make_temp_dir();
  // the analysis counts from the leader's first traced cycle, which under ASan on a busy host
  // comes a second or more after the launch: the run is long enough that the window still has data
  write_file(dir + "/e.yaml", "experiment:\n  name: tiny\n  duration_s: 6\n  seed: 7\n  profiles: [none]\n"
                              "  runs:\n    - {name: pfc_tdpa, scenario: " +
                                  source("config/scenarios/stiff_wall_pfc_tdpa.yaml") +
                                  "}\n"
                                  "  analysis: {settle_s: 0.5, hold_window_s: [1.5, 2.5]}\n");
  const ProcessResult experiment =
      run_process({bin("teleop"), "experiment", dir + "/e.yaml", "--report-dir", dir + "/out", "--domain",
                   std::to_string(unique_domain())},
                  std::chrono::seconds(90));
  ASSERT_EQ(experiment.exit_status, 0) << experiment.output;
  // every figure drawn (a node's own warnings, a loop stalled on a loaded host, are not the plot's)
  EXPECT_EQ(experiment.output.find("[experiment] warning"), std::string::npos) << experiment.output;
  const std::string run_dir = dir + "/out/pfc_tdpa/none";
  // the run's figures mark when its operator began (the leader's operator_s) and the hold window
  EXPECT_NE(experiment.output.find("teleop plot: marked the operator's start at "), std::string::npos) << experiment.output;
  EXPECT_NE(experiment.output.find(" and hold 1.5-2.5 s after it (" + run_dir + ")"), std::string::npos)
      << experiment.output;
  // and metrics that are not zero in any run: their bars show
  std::vector<std::string> figures = pngs(run_dir, "", kRunFigures);
  for (const std::string& f : pngs(dir + "/out", "tiny_", {"force_felt_n", "tracking_rmse_m", "mad_rad"})) {
    figures.push_back(f);
  }
  expect_figures_drawn(figures);

  const ProcessResult plot =
      run_process({bin("teleop"), "plot", run_dir, "-o", dir + "/again"}, std::chrono::seconds(60));
  EXPECT_EQ(plot.exit_status, 0) << plot.output;
  for (const std::string& f : pngs(dir + "/again", "", kRunFigures)) {
    EXPECT_NE(plot.output.find("wrote " + f), std::string::npos) << plot.output;
    EXPECT_GT(fs::file_size(f), 10'000u) << f;
  }
}

// a recording as `teleop record` writes it (three samples of every teleop type): `teleop bag
// export` writes its topics as CSV, `teleop plot` exports and draws them
TEST(PlotProcess, ARecordingsTopicsAreExportedAndDrawn) {
  const std::string dir = make_temp_dir();
  const std::string recording = dir + "/r.mcap";
  ASSERT_EQ(run_process({bin("write_sample_mcap"), recording}, std::chrono::seconds(30)).exit_status, 0);
  const ProcessResult exported = run_process({bin("teleop"), "bag", "export", recording}, std::chrono::seconds(30));
  EXPECT_EQ(exported.exit_status, 0) << exported.output;
  const std::string state_csv = recording + "_csv/teleop.sample.teleop.msg.JointState.csv";
  EXPECT_NE(exported.output.find("wrote " + state_csv + ": 3 rows"), std::string::npos) << exported.output;

  const ProcessResult plot = run_process({bin("teleop"), "plot", recording}, std::chrono::seconds(60));
  EXPECT_EQ(plot.exit_status, 0) << plot.output;
  const std::string out = recording + "_plots/teleop.sample.teleop.msg.";
  expect_figures_drawn({out + "JointState_positions.png", out + "WrenchStamped_wrench.png", out + "JointTorque_torques.png"});
}

TEST(PlotProcess, AFolderWithoutTracesIsAnErrorNamingIt) {
  const std::string dir = make_temp_dir();
  write_file(dir + "/notes.csv", "run,profile\n");
  const ProcessResult r = run_process({bin("teleop"), "plot", dir}, std::chrono::seconds(30));
  EXPECT_EQ(r.exit_status, 1) << r.output;
  EXPECT_NE(r.output.find("teleop plot: " + dir + ": no trace in this directory"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir + "/position.png"));
}

}  // namespace
}  // namespace teleop::test
