// The SVH hand study (teleop hand-study): the study file, one run at rest in contact at the
// paper's inertia (no MuJoCo warning, every joint still to machine precision, a steady tip force),
// and the report beside the paper's tables. The runs start in the "test" pose and simulate 2 s
// (the sanitizer build runs this too); the full motion from "home" is the command's.
#include "teleop/experiment/hand_study.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "allocation_counter.h"
#include "teleop/common/config.h"
#include "teleop/experiment/hand_study_simulation.h"
#include "test_helpers.h"

namespace teleop::experiment {
namespace {

std::string source(const std::string& path) { return std::string(TELEOP_SOURCE_DIR) + "/" + path; }

// the study file's settings, held in the pose Table I calls "test" from the start
HandStudyConfig resting_in_contact() {
  HandStudyConfig c = load_hand_study(source("config/experiments/hand_contact.yaml"));
  c.path = {{"test", 0.0}};
  c.settle_s = 1.5;
  c.record_s = 0.5;
  return c;
}

HandStudyRun run_named(const HandStudyConfig& c, const std::string& name) {
  for (const HandStudyRun& r : c.runs) {
    if (r.name == name) return r;
  }
  ADD_FAILURE() << "no run " << name;
  return {};
}

// one simulation shared by the tests that look at it
class PaperInertiaAtRest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    config_ = new HandStudyConfig(resting_in_contact());
    result_ = new HandStudyRunResult(run_hand_study_case(*config_, run_named(*config_, "I0.1")));
  }
  static void TearDownTestSuite() {
    delete result_;
    delete config_;
  }
  static HandStudyConfig* config_;
  static HandStudyRunResult* result_;
};
HandStudyConfig* PaperInertiaAtRest::config_ = nullptr;
HandStudyRunResult* PaperInertiaAtRest::result_ = nullptr;

TEST_F(PaperInertiaAtRest, RunsWithoutAnyMuJoCoWarningOrContactButTheFingertips) {
  EXPECT_EQ(result_->run.link_inertia_kgm2, 0.1);
  EXPECT_EQ(result_->mujoco_warnings, 0);
  EXPECT_EQ(result_->foreign_contact_steps, 0);
  EXPECT_TRUE(result_->sound());
  // the mechanism holds while the hand presses: the couplings within a milliradian
  EXPECT_LT(result_->coupling_residual_max_rad, 1e-3);
}

TEST_F(PaperInertiaAtRest, EveryJointRestsBelowOneNanoradianOfMad) {
  ASSERT_EQ(result_->mad_rad.size(), hand_study_joints().size());
  ASSERT_EQ(hand_study_joints().size(), 26u);
  for (size_t j = 0; j < result_->mad_rad.size(); ++j) {
    EXPECT_LT(result_->mad_rad[j], 1e-9) << hand_study_joints()[j];
  }
  // 50 samples at 100 Hz in the window, each MAD over those whose 10-sample window fits
  EXPECT_NEAR(result_->t_s.back() - result_->record_begin_s, 0.5, 1e-9);
  std::printf("MAD at 0.1 kg m^2 from rest: average of the paper's 15 %.3g rad, max of 26 %.3g rad\n",
              result_->mad_paper_average_rad, result_->mad_max_rad);
}

TEST_F(PaperInertiaAtRest, TheTipForceSettlesToASteadyNonZeroValue) {
  EXPECT_GT(result_->tip_force_min_n, 1.0);
  EXPECT_LT(result_->tip_force_max_n - result_->tip_force_min_n, 1e-6 * result_->tip_force_mean_n);
  EXPECT_LT(result_->tip_force_sd_n, 1e-6 * result_->tip_force_mean_n);
  // the fingertip presses from the first step on (the panel's face is 2 mm inside the free tip)
  EXPECT_NEAR(result_->first_contact_s, config_->sample_period_s, 1e-9);
  std::printf("tip force %.4f N (min %.6f, max %.6f)\n", result_->tip_force_mean_n, result_->tip_force_min_n,
              result_->tip_force_max_n);
}

TEST(HandStudySimulation, AStepDoesNotAllocate) {
  HandStudyConfig c = resting_in_contact();
  c.path = {{"approach", 0.0}, {"test", 0.05}};  // a moving reference, then the contact
  HandStudySimulation simulation(c, run_named(c, "I0.01"));
  long foreign = 0;
  const test::ScopedAllocationCounter allocations;
  for (int k = 0; k < 100; ++k) {
    simulation.step();
    foreign += simulation.foreign_contact();
  }
  EXPECT_EQ(allocations.count(), 0u);
  EXPECT_EQ(foreign, 0);
  EXPECT_NEAR(simulation.time_s(), 0.1, 1e-12);
}

TEST(HandStudyFile, ReadsThePathTheControlAndTheRuns) {
  const HandStudyConfig c = load_hand_study(source("config/experiments/hand_contact.yaml"));
  EXPECT_EQ(c.name, "hand_contact");
  EXPECT_EQ(std::filesystem::path(c.model_path).filename(), "scene_ur5_svh.xml");
  ASSERT_EQ(c.path.size(), 3u);
  EXPECT_EQ(c.path.front().keyframe, "home");
  EXPECT_EQ(c.path.back().keyframe, "test");
  EXPECT_DOUBLE_EQ(c.motion_s(), 5.0);
  EXPECT_EQ(c.mad_window, 10u);
  EXPECT_DOUBLE_EQ(c.hand_torque_limit_nm, 100.0);
  ASSERT_EQ(c.runs.size(), 8u);
  EXPECT_EQ(c.runs[2].name, "I0.1");
  EXPECT_DOUBLE_EQ(c.runs[2].link_inertia_kgm2, 0.1);
  EXPECT_EQ(c.runs[2].coupling, hand::CouplingMode::kConstraint);
  EXPECT_EQ(c.runs[7].coupling, hand::CouplingMode::kServo);
  EXPECT_EQ(c.runs[7].link_inertia_kgm2, 0.0);
  const HandStudyConfig creep = load_hand_study(source("config/experiments/hand_contact_creep.yaml"));
  EXPECT_EQ(creep.friction_cone, "pyramidal");
  EXPECT_EQ(creep.noslip_iterations, 0);
}

TEST(HandStudyFile, ErrorsNameTheKey) {
  test::TempDir dir("hand_study_file");
  const std::string model = source("config/models/scene_ur5_svh.xml");
  const auto error_for = [&](const std::string& body) {
    const std::string path = dir.write("s.yaml", "hand_study:\n  name: s\n  model: " + model + "\n" + body);
    return test::error_of<ConfigError>([&] { load_hand_study(path); });
  };
  const std::string path = "  path: [{keyframe: test}]\n";
  EXPECT_NE(error_for(path).find("runs"), std::string::npos);
  EXPECT_NE(error_for("  runs: [{name: a}]\n").find("path"), std::string::npos);
  EXPECT_NE(error_for(path + "  runs: [{name: a, couplings: glue}]\n").find("couplings"), std::string::npos);
  EXPECT_NE(error_for(path + "  runs: [{name: a}, {name: a}]\n").find("second run"), std::string::npos);
  EXPECT_NE(error_for("  path: [{keyframe: home}, {keyframe: test}]\n  runs: [{name: a}]\n").find("move_s"),
            std::string::npos);
  EXPECT_NE(error_for(path + "  record_s: 0.05\n  runs: [{name: a}]\n").find("record_s"), std::string::npos);
  EXPECT_NE(error_for(path + "  runs: [{name: a, inertia: 1}]\n").find("inertia"), std::string::npos);
}

TEST(HandStudy, WritesItsFilesAndSetsOursBesideThePapersTables) {
  test::TempDir dir("hand_study_out");
  HandStudyConfig c = resting_in_contact();
  c.settle_s = 0.1;
  c.record_s = 0.2;
  HandStudyOptions options;
  options.out_dir = dir.path("out");
  options.runs = {"own", "own_servo"};
  options.plots = false;
  const HandStudyResult result = run_hand_study(c, options);
  ASSERT_EQ(result.runs.size(), 2u);
  for (const std::string& file : {result.mad_csv, result.runs_csv, result.trace_csv, result.markdown}) {
    EXPECT_TRUE(std::filesystem::exists(file)) << file;
  }
  std::ifstream in(result.markdown);
  std::stringstream markdown;
  markdown << in.rdbuf();
  const std::string text = markdown.str();
  // the paper's numbers beside ours: Table II's Thumb_Opposition at 0.001, Table III's average
  EXPECT_NE(text.find("| \"Thumb_Opposition\" |"), std::string::npos);
  EXPECT_NE(text.find("4.379e-04"), std::string::npos);
  EXPECT_NE(text.find("4.366e-17"), std::string::npos);
  EXPECT_NE(text.find("couplings as servos"), std::string::npos);
  // one MAD row per run and joint
  std::ifstream mad(result.mad_csv);
  size_t lines = 0;
  for (std::string line; std::getline(mad, line);) ++lines;
  EXPECT_EQ(lines, 1 + 2 * hand_study_joints().size());
  options.runs = {"nonesuch"};
  EXPECT_THROW(run_hand_study(c, options), std::runtime_error);
}

}  // namespace
}  // namespace teleop::experiment
