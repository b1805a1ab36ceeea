// Scenario `set:` entries and the launcher's NODE:KEY=VALUE overrides.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "teleop/common/config.h"
#include "teleop/launcher/launcher.h"
#include "teleop/launcher/scenario.h"
#include "test_helpers.h"

namespace teleop::launcher {
namespace {

using Strings = std::vector<std::string>;

Scenario two_nodes(const test::TempDir& dir, const std::string& leader_extra) {
  dir.write("node.yaml", "node: {}\n");
  return load_scenario(dir.write("s.yaml",
                                 "scenario: {name: s}\nnodes:\n"
                                 "  - {name: follower, executable: teleop_follower, config: node.yaml}\n"
                                 "  - name: leader\n    executable: teleop_leader\n    config: node.yaml\n" +
                                     leader_extra));
}

TEST(ScenarioOverrides, TurnsTheSetMappingIntoKeyValueArgumentsWithYamlValues) {
  test::TempDir dir("scenario_set");
  const Scenario s = two_nodes(dir,
                               "    set:\n      teleoperation.architecture: pfc_tdpa\n"
                               "      leader.amplitudes_rad: [0, 0.2, 0]\n");
  EXPECT_TRUE(s.nodes[0].sets.empty());
  EXPECT_EQ(s.nodes[1].sets, (Strings{"teleoperation.architecture=pfc_tdpa", "leader.amplitudes_rad=[0, 0.2, 0]"}));
}

TEST(ScenarioOverrides, AddsTheOptionsOverridesForTheirNodeOnlyAfterTheScenarios) {
  test::TempDir dir("scenario_set_options");
  const Scenario s = two_nodes(dir, "    set: {a.b: 1}\n");
  const Strings options{"leader:a.b=2", "follower:x={k: 1}", "leader:c=d:e"};
  EXPECT_EQ(node_overrides(s, s.nodes[1], options), (Strings{"a.b=1", "a.b=2", "c=d:e"}));
  EXPECT_EQ(node_overrides(s, s.nodes[0], options), (Strings{"x={k: 1}"}));
}

TEST(ScenarioOverrides, RejectsAnOverrideForAnUnknownNodeOrWithoutNode) {
  test::TempDir dir("scenario_set_bad");
  const Scenario s = two_nodes(dir, "");
  EXPECT_EQ(test::error_of<ConfigError>([&] { node_overrides(s, s.nodes[0], {"twin:a=1"}); }),
            "--set twin:a=1: scenario s has no node 'twin'");
  EXPECT_EQ(test::error_of<ConfigError>([&] { node_overrides(s, s.nodes[0], {"a=x:y"}); }),
            "--set a=x:y: expected NODE:KEY=VALUE, e.g. leader:node.rate_hz=500");
}

}  // namespace
}  // namespace teleop::launcher
