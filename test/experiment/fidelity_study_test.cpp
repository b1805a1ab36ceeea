// The fidelity study (teleop fidelity-study, docs/fidelity.md): the study file, the lock-step
// replay (bit-identical twice; exact when the "real" robot is the nominal one without noise), the
// perturbed robot against its replay, a step without allocation, and the report beside the
// thesis's tables. Short sequences (zero -> ready in 0.5 s); the full study is the command's.
#include "teleop/experiment/fidelity_study.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "allocation_counter.h"
#include "fidelity_arm.h"
#include "teleop/common/config.h"
#include "test_helpers.h"

namespace teleop::experiment {
namespace {

std::string source(const std::string& path) { return std::string(TELEOP_SOURCE_DIR) + "/" + path; }

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// the shipped file with short holds and movements, the free sequence from zero to ready
FidelityStudyConfig short_study() {
  FidelityStudyConfig c = load_fidelity_study(source("config/experiments/fidelity.yaml"));
  c.move_s = 0.5;
  c.hold_s = 0.4;
  c.pose_window_s = 0.2;
  c.sequences.at(0).path = {"zero", "ready"};
  return c;
}

const FidelitySequence& free_sequence(const FidelityStudyConfig& c) { return c.sequences.at(0); }

bool identical(const FidelityTrajectory& a, const FidelityTrajectory& b) {
  return a.q_rad == b.q_rad && a.dq_radps == b.dq_radps && a.tau_nm == b.tau_nm;
}

TEST(FidelityFile, ReadsThePosesTheSequencesTheControllersAndTheRealRobot) {
  const FidelityStudyConfig c = load_fidelity_study(source("config/experiments/fidelity.yaml"));
  EXPECT_EQ(c.name, "fidelity");
  EXPECT_GE(c.seeds.size(), 3u);
  ASSERT_EQ(c.sequences.size(), 2u);
  EXPECT_EQ(c.sequences[0].path, (std::vector<std::string>{"zero", "ready", "idle", "park", "idle", "ready", "zero"}));
  EXPECT_FALSE(c.sequences[0].contact);
  EXPECT_TRUE(c.sequences[1].contact);
  EXPECT_DOUBLE_EQ(c.pose("ready").q_rad[3], -2.356194);
  EXPECT_DOUBLE_EQ(c.state_space.kp[0], 2400);
  EXPECT_DOUBLE_EQ(c.joint_impedance.stiffness[6], 50);
  EXPECT_DOUBLE_EQ(c.perturbation.mass_fraction, 0.10);
  EXPECT_DOUBLE_EQ(c.sensor_noise.tau_nm, 0.05);
  EXPECT_THROW(c.pose("nonesuch"), std::out_of_range);
}

TEST(FidelityFile, ErrorsNameTheKeyAndTheProblem) {
  test::TempDir dir("fidelity_file");
  const std::string good = read_text(source("config/experiments/fidelity.yaml"));
  const auto error_for = [&](const std::string& from, const std::string& to) {
    std::string text = good;
    const size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
    // model paths stay valid from the temporary folder
    for (size_t p = text.find("../models/"); p != std::string::npos; p = text.find("../models/", p + 1)) {
      text.replace(p, 3, source("config/"));
    }
    const std::string path = dir.write("study.yaml", text);
    try {
      load_fidelity_study(path);
    } catch (const ConfigError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  // joint 4 at 0: outside the Panda's range
  const std::string range = error_for("q_rad: [0, 0, 0, -0.15, 0, 0.15, 0]", "q_rad: [0, 0, 0, 0, 0, 0.15, 0]");
  EXPECT_NE(range.find("path"), std::string::npos) << range;
  EXPECT_NE(range.find("joint 4"), std::string::npos) << range;
  const std::string unknown = error_for("path: [zero, ready, idle", "path: [zero, nowhere, idle");
  EXPECT_NE(unknown.find("nowhere"), std::string::npos) << unknown;
  const std::string seeds = error_for("seeds: [1, 2, 3]", "seeds: []");
  EXPECT_NE(seeds.find("seeds"), std::string::npos) << seeds;
  const std::string joints = error_for("kp: [2400, 2400, 2400, 2400, 1000, 600, 200]", "kp: [2400]");
  EXPECT_NE(joints.find("kp"), std::string::npos) << joints;
}

// the thesis's method on one short movement: record the real run's commands, replay them twice
TEST(FidelityReplay, ARunReplayedTwiceInLockStepGivesBitIdenticalTrajectories) {
  const FidelityStudyConfig c = short_study();
  for (const FidelityController controller : {FidelityController::kStateSpace, FidelityController::kJointImpedance}) {
    SCOPED_TRACE(controller_name(controller));
    std::vector<RecordedCommand> commands;
    const FidelityTrajectory real = run_real(c, free_sequence(c), controller, 1, commands);
    ASSERT_EQ(commands.size(), 1300u);  // 0.4 + 0.5 + 0.4 s at 1 ms
    const FidelityTrajectory first = replay(c, free_sequence(c), controller, commands);
    const FidelityTrajectory second = replay(c, free_sequence(c), controller, commands);
    ASSERT_EQ(first.q_rad.size(), commands.size());
    EXPECT_TRUE(identical(first, second));
    // and the real run differs from them (else the comparison would show nothing)
    EXPECT_FALSE(identical(real, first));
    EXPECT_EQ(first.mujoco_warnings, 0);
    EXPECT_EQ(real.mujoco_warnings, 0);
  }
}

TEST(FidelityReplay, TheSameSeedGivesTheSameRealRunBitForBit) {
  const FidelityStudyConfig c = short_study();
  std::vector<RecordedCommand> commands_a;
  std::vector<RecordedCommand> commands_b;
  std::vector<RecordedCommand> commands_c;
  const FidelityTrajectory a = run_real(c, free_sequence(c), FidelityController::kJointImpedance, 4, commands_a);
  const FidelityTrajectory b = run_real(c, free_sequence(c), FidelityController::kJointImpedance, 4, commands_b);
  const FidelityTrajectory other = run_real(c, free_sequence(c), FidelityController::kJointImpedance, 5, commands_c);
  EXPECT_TRUE(identical(a, b));
  EXPECT_FALSE(identical(a, other));
  EXPECT_EQ(a.perturbation.mass_factor, b.perturbation.mass_factor);
}

// with the nominal robot and perfect sensors as the "real" one, the replay is the real run: the
// recording carries everything the run depends on
TEST(FidelityReplay, ANominalRealRobotWithoutNoiseIsReplayedExactly) {
  FidelityStudyConfig c = short_study();
  c.perturbation = sim::PerturbationSpec{0.0, 0.0, 0.0, 0.0, 0.0};
  c.sensor_noise = sim::SensorNoiseSpec{0.0, 0.0, 0.0};
  for (const FidelityController controller : {FidelityController::kStateSpace, FidelityController::kJointImpedance}) {
    std::vector<RecordedCommand> commands;
    const FidelityTrajectory real = run_real(c, free_sequence(c), controller, 1, commands);
    EXPECT_TRUE(identical(real, replay(c, free_sequence(c), controller, commands))) << controller_name(controller);
  }
  const FidelityRun run = run_fidelity_case(c, free_sequence(c), FidelityController::kJointImpedance, 1);
  for (const FidelitySegment& g : run.segments) {
    EXPECT_EQ(g.q_rmse_deg.max, 0.0) << g.name;
    EXPECT_EQ(g.tau_rmse_nm.max, 0.0) << g.name;
    EXPECT_EQ(g.ee_position_cm.max, 0.0) << g.name;
    EXPECT_EQ(g.ee_rotation.max, 0.0) << g.name;
  }
}

TEST(FidelityRun, ThePerturbedRobotStaysCloseToItsTwinButNotEqualPerPoseAndMovement) {
  const FidelityStudyConfig c = short_study();
  for (const FidelityController controller : {FidelityController::kStateSpace, FidelityController::kJointImpedance}) {
    SCOPED_TRACE(controller_name(controller));
    const FidelityRun run = run_fidelity_case(c, free_sequence(c), controller, 2);
    EXPECT_EQ(run.mujoco_warnings, 0);
    ASSERT_EQ(run.segments.size(), 3u);
    EXPECT_EQ(run.segments[0].name, "zero");
    EXPECT_EQ(run.segments[1].name, "zero_to_ready");
    EXPECT_TRUE(run.segments[1].movement);
    EXPECT_EQ(run.segments[2].name, "ready");
    // the movement's window: 0.2 s before it starts to 0.4 s after it ends
    EXPECT_DOUBLE_EQ(run.segments[1].window.begin_s, 0.2);
    EXPECT_DOUBLE_EQ(run.segments[1].window.end_s, 1.3);
    for (const FidelitySegment& g : run.segments) {
      SCOPED_TRACE(g.name);
      EXPECT_GT(g.q_rmse_deg.mean, 0.0);
      EXPECT_LT(g.q_rmse_deg.max, 2.0);  // degrees: a twin, not another robot
      // an RMSE never exceeds its largest error (a movement's at any sample; a pose's is averaged)
      if (g.movement) {
        EXPECT_LE(g.q_rmse_deg.max, g.q_max_joint_deg);
      }
      EXPECT_GT(g.q_max_joint_deg, 0.0);
      EXPECT_GT(g.tau_rmse_nm.mean, 0.0);
      EXPECT_LT(g.tau_rmse_nm.max, 20.0);
      EXPECT_GT(g.ee_position_cm.mean, 0.0);
      EXPECT_LT(g.ee_position_cm.max, 3.0);
      EXPECT_GT(g.ee_rotation.mean, 0.0);
      EXPECT_LT(g.ee_rotation.max, 0.1);
    }
    EXPECT_GT(run.rt_factor_free, 1.0);              // in process: faster than real time on any machine here
    EXPECT_TRUE(std::isnan(run.rt_factor_contact));  // panda.xml has nothing to touch
    // poses: the mean of the two poses' means, the larger of them; movements: the peak sample
    const FidelityCell poses = aggregate(run, false);
    EXPECT_DOUBLE_EQ(poses.q_rmse_deg.mean, (run.segments[0].q_rmse_deg.mean + run.segments[2].q_rmse_deg.mean) / 2);
    EXPECT_DOUBLE_EQ(poses.q_rmse_deg.max, std::max(run.segments[0].q_rmse_deg.mean, run.segments[2].q_rmse_deg.mean));
    EXPECT_DOUBLE_EQ(aggregate(run, true).q_rmse_deg.max, run.segments[1].q_rmse_deg.max);
  }
}

TEST(FidelityRun, TheWallSequenceTouchesAndTimesItsContactSteps) {
  FidelityStudyConfig c = short_study();
  const FidelitySequence& wall = c.sequences.at(1);
  const FidelityRun run = run_fidelity_case(c, wall, FidelityController::kJointImpedance, 1);
  EXPECT_EQ(run.mujoco_warnings, 0);
  EXPECT_GT(run.contact_steps, 100u);
  EXPECT_GT(run.rt_factor_contact, 1.0);
}

TEST(FidelityArm, AStepDoesNotAllocate) {
  const FidelityStudyConfig c = short_study();
  for (const bool real : {false, true}) {
    FidelityArm arm(c, free_sequence(c).model_path, FidelityController::kJointImpedance,
                    real ? std::optional<uint64_t>(3) : std::nullopt);
    arm.place(c.pose("ready").q_rad);
    RecordedCommand command;
    command.q_d = c.pose("ready").q_rad;
    arm.step(command);
    test::ScopedAllocationCounter allocations;
    for (int k = 0; k < 100; ++k) arm.step(command);
    EXPECT_EQ(allocations.count(), 0u) << (real ? "real" : "twin");
  }
}

TEST(FidelityStudy, WritesItsFilesAndSetsOursBesideTheThesissTables) {
  test::TempDir dir("fidelity_out");
  const FidelityStudyConfig c = short_study();
  FidelityStudyOptions options;
  options.out_dir = dir.path("out");
  options.seeds = {1, 2};
  options.sequences = {"free"};
  options.plots = false;
  const FidelityStudyResult result = run_fidelity_study(c, options);
  ASSERT_EQ(result.runs.size(), 4u);  // 2 controllers x 2 seeds
  EXPECT_TRUE(result.sound());
  for (const std::string& file : {result.segments_csv, result.runs_csv, result.trace_csv, result.markdown}) {
    EXPECT_TRUE(std::filesystem::exists(file)) << file;
  }
  const std::string text = read_text(result.markdown);
  // the thesis's numbers beside ours: Table 4.1's arm mean RMSE of state-space poses, Table
  // 4.2's largest joint-impedance movement torque error, §4.3.2's position error, §4.5's RTF
  EXPECT_NE(text.find("## Table 4.1"), std::string::npos);
  EXPECT_NE(text.find("| Arm Mean RMSE |"), std::string::npos);
  EXPECT_NE(text.find("0.0568"), std::string::npos);
  EXPECT_NE(text.find("5.091"), std::string::npos);
  EXPECT_NE(text.find("1.89"), std::string::npos);
  EXPECT_NE(text.find("0.86"), std::string::npos);
  EXPECT_NE(text.find("no torso"), std::string::npos);
  EXPECT_NE(text.find("zero_to_ready"), std::string::npos);
  // a row per run and segment; the trace every 10 ms
  const std::string segments = read_text(result.segments_csv);
  EXPECT_EQ(std::count(segments.begin(), segments.end(), '\n'), 1 + 4 * 3);
  const std::string trace = read_text(result.trace_csv);
  EXPECT_EQ(std::count(trace.begin(), trace.end(), '\n'), 1 + 4 * 130);
  options.sequences = {"nonesuch"};
  EXPECT_THROW(run_fidelity_study(c, options), std::runtime_error);
}

}  // namespace
}  // namespace teleop::experiment
