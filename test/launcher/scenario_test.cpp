// How a scenario finds its node configs: by a path relative to the scenario, or by name.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "teleop/common/config.h"
#include "teleop/launcher/scenario.h"
#include "test_helpers.h"

namespace teleop::launcher {
namespace {
namespace fs = std::filesystem;

std::string one_node(const std::string& config) {
  return "scenario: {name: s}\nnodes:\n  - {name: follower, executable: teleop_follower, config: " + config + "}\n";
}

fs::path root_of(const test::TempDir& dir) { return fs::path(dir.path("x")).parent_path(); }

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

TEST(Scenario, ANameIsAShippedNodeConfigWhereverTheScenarioLives) {
  test::TempDir dir("scenario_by_name");
  const Scenario s = load_scenario(dir.write("copied.yaml", one_node("follower")));
  ASSERT_EQ(s.nodes.size(), 1u);
  EXPECT_TRUE(ends_with(s.nodes[0].config, "config/nodes/follower.yaml")) << s.nodes[0].config;
  EXPECT_TRUE(fs::is_regular_file(s.nodes[0].config));
}

TEST(Scenario, APathIsRelativeToTheScenarioNotToTheWorkingDirectory) {
  test::TempDir dir("scenario_by_path");
  fs::create_directories(root_of(dir) / "mine");
  fs::create_directories(root_of(dir) / "scenarios");
  dir.write("mine/follower.yaml", "node: {}\n");
  const std::string file = dir.write("scenarios/s.yaml", one_node("../mine/follower.yaml"));
  const fs::path cwd = fs::current_path();
  fs::current_path(fs::temp_directory_path());
  const Scenario s = load_scenario(file);
  fs::current_path(cwd);
  EXPECT_EQ(fs::path(s.nodes[0].config), (root_of(dir) / "mine/follower.yaml").lexically_normal());
}

TEST(Scenario, AFileBesideTheScenarioWinsOverTheShippedConfigOfThatName) {
  test::TempDir dir("scenario_beside");
  dir.write("follower", "node: {}\n");
  const Scenario s = load_scenario(dir.write("s.yaml", one_node("follower")));
  EXPECT_EQ(fs::path(s.nodes[0].config), (root_of(dir) / "follower").lexically_normal());
}

TEST(Scenario, AnUnknownNameSaysWhereItLookedAndWhatWasMeant) {
  test::TempDir dir("scenario_typo");
  const std::string file = dir.write("s.yaml", one_node("folower"));
  const std::string error = test::error_of<ConfigError>([&] { load_scenario(file); });
  EXPECT_NE(error.find("nodes[0].config"), std::string::npos) << error;
  EXPECT_NE(error.find("did you mean 'follower'"), std::string::npos) << error;
}

TEST(Scenario, AMissingPathNamesTheFileItLookedFor) {
  test::TempDir dir("scenario_missing");
  const std::string file = dir.write("s.yaml", one_node("../nodes/follower.yaml"));
  const std::string error = test::error_of<ConfigError>([&] { load_scenario(file); });
  EXPECT_NE(error.find("nodes[0].config: file " + (root_of(dir).parent_path() / "nodes/follower.yaml").string() +
                       " does not exist"),
            std::string::npos)
      << error;
}

}  // namespace
}  // namespace teleop::launcher
