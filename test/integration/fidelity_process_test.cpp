// `teleop fidelity-study` as a real process (docs/fidelity.md): a reduced study (one movement in
// free space, one into the wall, two "real" robots, short holds) writes its CSVs, the report with
// the thesis's numbers beside ours, and its figures, which png_check.py opens; a second run of the
// same seeds gives the same numbers (the study is deterministic but for its timing). A few seconds.
// The wiping study (`teleop fidelity-study wiping`) as shipped: its tables, its figure, and the
// same files again with one worker process instead of two. A few seconds.
#include <gtest/gtest.h>

#include <filesystem>

#include "figure_check.h"
#include "process_helpers.h"
#include "teleop/experiment/plots.h"

namespace teleop::test {
namespace {

// a hang guard, not a speed limit: under ASan on a loaded host the shipped wiping study takes
// minutes; the ctest timeout (300 s) stays above it
constexpr std::chrono::seconds kStudyTimeout{280};

namespace fs = std::filesystem;

// the shipped study with short holds and movements, its models by absolute path
std::string reduced_study(const std::string& dir) {
  std::string text = read_file(source("config/experiments/fidelity.yaml"));
  const auto replace = [&](const std::string& from, const std::string& to) {
    const size_t at = text.find(from);
    if (at == std::string::npos) throw std::runtime_error("the shipped study has no '" + from + "'");
    text.replace(at, from.size(), to);
  };
  replace("path: [zero, ready, idle, park, idle, ready, zero]", "path: [zero, ready]");
  replace("move_s: 3.0", "move_s: 1.0");
  replace("hold_s: 2.0", "hold_s: 0.6");
  for (size_t p = text.find("../models/"); p != std::string::npos; p = text.find("../models/", p + 1)) {
    text.replace(p, 3, source("config/"));
  }
  write_file(dir + "/study.yaml", text);
  return dir + "/study.yaml";
}

// the lines of the report from Table 4.1 on (the real-time factors, wall-clock, left out)
std::string tables_of(const std::string& report) {
  const size_t begin = report.find("## Table 4.1");
  const size_t end = report.find("## Real-time factor");
  return begin == std::string::npos || end == std::string::npos ? std::string() : report.substr(begin, end - begin);
}

TEST(FidelityStudyProcess, WritesTheReportBesideTheThesisAndItsFiguresAndRepeatsItsNumbers) {
  const std::string dir = make_temp_dir();
  const std::string study = reduced_study(dir);
  const ProcessResult first = run_process(
      {bin("teleop"), "fidelity-study", study, "-o", dir + "/one", "--seeds", "1,2"}, std::chrono::seconds(120));
  ASSERT_EQ(first.exit_status, 0) << first.output;
  EXPECT_EQ(first.output.find("warning"), std::string::npos) << first.output;
  for (const std::string name : {"segments.csv", "runs.csv", "trace.csv", "md"}) {
    EXPECT_TRUE(fs::exists(dir + "/one/fidelity_" + name) || fs::exists(dir + "/one/fidelity." + name)) << name;
  }
  const std::string report = read_file(dir + "/one/fidelity.md");
  EXPECT_NE(report.find("| Arm Mean RMSE |"), std::string::npos) << report;
  EXPECT_NE(report.find("| 0.0568 |"), std::string::npos) << report;  // Table 4.1, state space poses
  EXPECT_NE(report.find("| 1.223 |"), std::string::npos) << report;   // Table 4.2, state space poses
  EXPECT_NE(report.find("## In contact"), std::string::npos) << report;
  EXPECT_NE(report.find("zero_to_ready"), std::string::npos) << report;
  EXPECT_NE(first.output.find("report: " + dir + "/one/fidelity.md"), std::string::npos) << first.output;

  // the figures: per movement (free space) and the contact sequence's
  std::vector<std::string> figures;
  for (const std::string name :
       {"free_joint_error", "free_torque_error", "free_ee_position_error", "free_ee_rotation_error", "contact"}) {
    figures.push_back(dir + "/one/fidelity_" + name + ".png");
    EXPECT_NE(first.output.find("wrote " + figures.back()), std::string::npos) << first.output;
  }
  expect_figures_drawn(figures);

  // the same seeds again, no figures: the same tables, digit for digit
  const ProcessResult second =
      run_process({bin("teleop"), "fidelity-study", study, "-o", dir + "/two", "--seeds", "1,2", "--no-plots"},
                  std::chrono::seconds(120));
  ASSERT_EQ(second.exit_status, 0) << second.output;
  const std::string tables = tables_of(report);
  EXPECT_FALSE(tables.empty()) << report;
  EXPECT_EQ(tables_of(read_file(dir + "/two/fidelity.md")), tables);
  EXPECT_EQ(read_file(dir + "/two/fidelity_segments.csv"), read_file(dir + "/one/fidelity_segments.csv"));
}

TEST(FidelityStudyProcess, AnUnknownSequenceIsAnErrorNamingIt) {
  const std::string dir = make_temp_dir();
  const ProcessResult r =
      run_process({bin("teleop"), "fidelity-study", reduced_study(dir), "-o", dir + "/out", "--sequences", "nowhere"},
                  std::chrono::seconds(60));
  EXPECT_EQ(r.exit_status, 1) << r.output;
  EXPECT_NE(r.output.find("no sequence 'nowhere'"), std::string::npos) << r.output;
}

TEST(WipingStudyProcess, WritesTablesBesideTheThesisAndItsFigureAndRepeatsThemWithOneWorker) {
  const std::string dir = make_temp_dir();
  const ProcessResult first =
      run_process({bin("teleop"), "fidelity-study", "wiping", "-o", dir + "/two", "-j", "2"}, kStudyTimeout);
  ASSERT_EQ(first.exit_status, 0) << first.output;
  EXPECT_EQ(first.output.find("[fidelity-study] warning"), std::string::npos) << first.output;
  const std::string report = read_file(dir + "/two/wiping.md");
  // Table 4.3's shape: ours (the shipped grid has cells with every wipe and with none in contact)
  // and the thesis's beside it
  EXPECT_NE(report.find("| 0.000 rad | 3/3 contacts |"), std::string::npos) << report;
  EXPECT_NE(report.find("| -0.150 rad | no contacts |"), std::string::npos) << report;
  EXPECT_NE(report.find("| 0.0 rad | 2/3 contacts | 3/3 contacts | 3/3 contacts |"), std::string::npos) << report;
  // Table 4.4's shape and the real robot's peaks
  EXPECT_NE(report.find("J0: 14/12/8 N m, J3: 8/8/6 N m"), std::string::npos) << report;
  EXPECT_NE(first.output.find("sweep: 9 cells in 2 worker processes"), std::string::npos) << first.output;

  std::vector<std::string> figures;
  for (const std::string name : {"torque_peaks", "torques_over_time", "hand_height"}) {
    figures.push_back(dir + "/two/wiping_" + name + ".png");
    EXPECT_NE(first.output.find("wrote " + figures.back()), std::string::npos) << first.output;
  }
  expect_figures_drawn(figures);

#ifndef TELEOP_SANITIZED
  // one worker: the same cells, byte for byte (a property of the arithmetic, not of memory: the
  // sanitizer build, where the study takes a minute a run, checks the pool in
  // experiment_sweep_workers_test instead)
  const ProcessResult second = run_process(
      {bin("teleop"), "fidelity-study", "wiping", "-o", dir + "/one", "-j", "1", "--no-plots"}, kStudyTimeout);
  ASSERT_EQ(second.exit_status, 0) << second.output;
  EXPECT_EQ(read_file(dir + "/one/wiping.md"), report);
  EXPECT_EQ(read_file(dir + "/one/wiping_wipes.csv"), read_file(dir + "/two/wiping_wipes.csv"));
  EXPECT_EQ(read_file(dir + "/one/wiping_trace.csv"), read_file(dir + "/two/wiping_trace.csv"));
#endif
}

TEST(WipingStudyProcess, TheAccuracyStudysOptionsAreAnErrorNotIgnored) {
  const std::string dir = make_temp_dir();
  const ProcessResult r = run_process(
      {bin("teleop"), "fidelity-study", "wiping", "-o", dir + "/out", "--seeds", "1,2"}, std::chrono::seconds(60));
  EXPECT_EQ(r.exit_status, 1) << r.output;
  EXPECT_NE(r.output.find("is a wiping study"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir + "/out/wiping.md"));
}

}  // namespace
}  // namespace teleop::test
