// Parameter sweeps: the grid, its configuration errors, and the press scenario's outcomes.
#include "parameter_sweep.h"

#include <gtest/gtest.h>

#include <string>

namespace teleop::experiment {
namespace {

std::string model_path(const std::string& name) { return std::string(TELEOP_SOURCE_DIR) + "/config/models/" + name; }

SweepConfig wiping(std::vector<SweepParameter> parameters) {
  SweepConfig c;
  c.model.model_path = model_path("scene_wiping.xml");
  c.model.keyframe = "ready";
  c.model.contact_pairs = {{"wiper_panel", "body:wiper", "geom:panel"}};
  c.duration_s = 1.2;
  c.parameters = std::move(parameters);
  return c;
}

TEST(SweepGrid, HoldsEveryCombinationWithTheFirstParameterSlowest) {
  const auto grid = sweep_grid({{"a", "press_depth_m", {1, 2}}, {"b", "press_depth_m", {10, 20, 30}}});
  ASSERT_EQ(grid.size(), 6u);
  EXPECT_EQ(grid[0], (std::vector<double>{1, 10}));
  EXPECT_EQ(grid[2], (std::vector<double>{1, 30}));
  EXPECT_EQ(grid[3], (std::vector<double>{2, 10}));
}

TEST(SweepConfig, RejectsAnUnknownParameterKindNamingTheKey) {
  const auto root = ConfigNode::load_string(
      "sweep:\n  model: {file: " + model_path("scene_wiping.xml") +
          "}\n  press: {}\n  parameters:\n    - {name: x, set: \"mass:link1\", values: [1]}\n",
      "sweep.yaml");
  try {
    parse_sweep_config(root);
    FAIL() << "accepted an unknown parameter";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("sweep.parameters[0].set"), std::string::npos) << e.what();
  }
}

TEST(PressScenario, PressesHarderOnAHigherPanel) {
  const SweepConfig config = wiping({{"panel_height_m", "geom_pos_z:panel", {}}});
  const VariantOutcome low = run_press_variant(config, {0.27});
  const VariantOutcome high = run_press_variant(config, {0.33});
  ASSERT_EQ(low.error, "");
  ASSERT_EQ(high.error, "");
  EXPECT_GT(low.contact_steps, 0);
  EXPECT_GT(high.contact_steps, low.contact_steps) << "a higher panel is met earlier";
  EXPECT_GT(high.mean_force_n, low.mean_force_n + 10.0) << "its surface lies 6 cm further in front of the target";
  EXPECT_EQ(low.mujoco_warnings + high.mujoco_warnings, 0);
}

TEST(PressScenario, ReportsABadParameterAsAnErrorNotACrash) {
  const SweepConfig config = wiping({{"x", "geom_pos_z:no_such_geom", {}}});
  const VariantOutcome o = run_press_variant(config, {0.1});
  EXPECT_NE(o.error.find("no_such_geom"), std::string::npos) << o.error;
}

}  // namespace
}  // namespace teleop::experiment
