// Experiment files: what is read, and errors that name the file and the key.
#include "teleop/experiment/experiment_config.h"

#include <gtest/gtest.h>

#include "teleop/common/config.h"
#include "test_helpers.h"

namespace teleop::experiment {
namespace {

class ExperimentFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_.write("node.yaml", "node: {}\n");
    dir_.write("scenario.yaml",
               "scenario: {name: s}\nnodes:\n"
               "  - {name: follower, executable: teleop_follower, config: node.yaml}\n"
               "  - {name: leader, executable: teleop_leader, config: node.yaml}\n");
  }
  std::string write(const std::string& body) { return dir_.write("e.yaml", "experiment:\n" + body); }
  std::string error_for(const std::string& body) {
    const std::string path = write(body);
    return test::error_of<ConfigError>([&] { load_experiment(path); });
  }
  static constexpr const char* kRuns = "  runs:\n    - {name: pfc, scenario: scenario.yaml}\n";
  test::TempDir dir_{"experiment_file"};
};

TEST_F(ExperimentFile, ReadsEveryFieldAndResolvesScenariosNextToTheFile) {
  const ExperimentConfig c = load_experiment(
      write("  name: stiff_wall\n  duration_s: 10\n  seed: 7\n  profiles: [lan, none]\n" + std::string(kRuns) +
            "    - {name: mmt, scenario: ./scenario.yaml, set: [\"leader:node.rate_hz=500\"]}\n"
            "  analysis:\n    leader: leader\n    follower: follower\n    settle_s: 1.5\n"
            "    hold_window_s: [6.0, 9.5]\n    stable_max_mad_rad: 2.0e-4\n    stable_max_saturation: 0.02\n"));
  EXPECT_EQ(c.name, "stiff_wall");
  EXPECT_DOUBLE_EQ(c.duration_s, 10.0);
  EXPECT_EQ(c.seed, 7u);
  EXPECT_EQ(c.profiles, (std::vector<std::string>{"lan", "none"}));
  ASSERT_EQ(c.runs.size(), 2u);
  EXPECT_EQ(c.runs[1].name, "mmt");
  EXPECT_EQ(c.runs[1].scenario, dir_.path("scenario.yaml"));
  EXPECT_TRUE(c.runs[0].sets.empty());
  EXPECT_EQ(c.runs[1].sets, (std::vector<std::string>{"leader:node.rate_hz=500"}));
  EXPECT_DOUBLE_EQ(c.analysis.settle_s, 1.5);
  EXPECT_DOUBLE_EQ(c.analysis.hold.begin_s, 6.0);
  EXPECT_DOUBLE_EQ(c.analysis.hold.end_s, 9.5);
  EXPECT_DOUBLE_EQ(c.analysis.stable_max_mad_rad, 2e-4);
  EXPECT_DOUBLE_EQ(c.analysis.stable_max_saturation, 0.02);
}

TEST_F(ExperimentFile, UsesAnalysisDefaultsWhenTheSectionIsAbsent) {
  const ExperimentConfig c = load_experiment(write("  name: x\n  profiles: [none]\n" + std::string(kRuns)));
  EXPECT_EQ(c.analysis.leader, "leader");
  EXPECT_DOUBLE_EQ(c.analysis.hold.begin_s, 6.0);
  EXPECT_DOUBLE_EQ(c.analysis.hold.end_s, 10.0);
}

TEST_F(ExperimentFile, NamesFileAndKeyOfEachProblem) {
  const std::string file = dir_.path("e.yaml");
  EXPECT_EQ(error_for("  name: x\n  profiles: [none]\n  runs: []\n"),
            file + ":4: experiment.runs: an experiment needs at least one run");
  EXPECT_EQ(error_for("  name: x\n" + std::string(kRuns)),
            file + ":2: experiment.profiles: needs at least one network profile ('none' = unimpaired)");
  EXPECT_EQ(error_for("  name: x\n  duration_s: 0\n  profiles: [none]\n" + std::string(kRuns)),
            file + ":3: experiment.duration_s: value 0 is out of range [0.1, 100000]");
  EXPECT_EQ(error_for("  name: x\n  profiles: [none]\n  runs:\n    - {name: a, scenario: nope.yaml}\n"),
            file + ":5: experiment.runs[0].scenario: no file " + dir_.path("nope.yaml"));
  EXPECT_EQ(error_for("  name: x\n  profiles: [none]\n" + std::string(kRuns) +
                      "    - {name: pfc, scenario: scenario.yaml}\n"),
            file + ":6: experiment.runs[1].name: 'pfc' is used by two runs");
  EXPECT_EQ(error_for("  name: x\n  profiles: [none]\n" + std::string(kRuns) + "  analysis: {hold_window_s: [5, 2]}\n"),
            file +
                ":6: experiment.analysis.hold_window_s: expected [begin, end] with begin < end (seconds after the "
                "operator began)");
  EXPECT_EQ(error_for("  name: x\n  profiles: [none]\n" + std::string(kRuns) + "  analysis: {settle: 1}\n"),
            file + ":6: experiment.analysis.settle: unknown key");
}

TEST_F(ExperimentFile, ReadsTheBoxTasksArmsAndTheShelfRegionOfItsScene) {
  const std::string scene = std::string(TELEOP_SOURCE_DIR) + "/config/models/scene_box_shelf.xml";
  const auto config = load_experiment(write("  name: x\n  profiles: [none]\n" + std::string(kRuns) +
                                            "  analysis: {task: box_task, arms: [left, right], scene: " + scene + "}\n"));
  EXPECT_EQ(config.analysis.kind, AnalysedTask::kBoxTask);
  EXPECT_EQ(config.analysis.arms, (std::vector<std::string>{"left", "right"}));
  // the shelf compartment of docs/box_task.md: box centre x 0.58-0.62, z 0.885-0.91 m
  EXPECT_TRUE(config.analysis.shelf.contains({0.60, 0.0, 0.89}));
  EXPECT_FALSE(config.analysis.shelf.contains({0.35, 0.0, 0.80})) << "the socket is not the shelf";
}

TEST_F(ExperimentFile, NamesTheKeyOfABoxTaskWithoutArmsOrWithASceneWithoutAShelf) {
  const std::string file = dir_.path("e.yaml");
  const std::string base = "  name: x\n  profiles: [none]\n" + std::string(kRuns);
  EXPECT_EQ(error_for(base + "  analysis: {task: box_task, scene: node.yaml}\n"),
            file + ":6: experiment.analysis.arms: the box task needs the arms whose columns the traces prefix, e.g. "
                   "[left, right]");
  const std::string wall = std::string(TELEOP_SOURCE_DIR) + "/config/models/scene_wall.xml";
  EXPECT_NE(error_for(base + "  analysis: {task: box_task, arms: [left], scene: " + wall + "}\n")
                .find(file + ":6: experiment.analysis.scene: "),
            std::string::npos);
}

TEST_F(ExperimentFile, NamesTheRunWhenItsScenarioIsInvalid) {
  dir_.write("bad_scenario.yaml", "scenario: {name: s}\nnodes: []\n");
  const std::string e =
      error_for("  name: x\n  profiles: [none]\n  runs:\n    - {name: a, scenario: bad_scenario.yaml}\n");
  EXPECT_NE(e.find(dir_.path("e.yaml") + ":5: experiment.runs[0].scenario: invalid scenario: "), std::string::npos)
      << e;
  EXPECT_NE(e.find("bad_scenario.yaml:2: nodes: a scenario needs at least one node"), std::string::npos) << e;
}

TEST_F(ExperimentFile, NamesTheRunWhenAnOverrideNamesNoNodeOfItsScenario) {
  const std::string e =
      error_for("  name: x\n  profiles: [none]\n  runs:\n    - {name: a, scenario: scenario.yaml, set: [\"twin:a=1\"]}\n");
  EXPECT_NE(e.find(dir_.path("e.yaml") + ":5: experiment.runs[0].set: --set twin:a=1: scenario s has no node 'twin'"),
            std::string::npos)
      << e;
}

}  // namespace
}  // namespace teleop::experiment
