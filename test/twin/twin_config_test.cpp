// The twin's configuration: errors name file, key and problem.
#include "teleop/twin/twin_config.h"

#include <gtest/gtest.h>

#include "twin_test_util.h"

namespace teleop::twin {
namespace {

std::string twin_yaml(const std::string& extra_model, const std::string& extra_twin = "") {
  return "twin:\n  joints: 7\n" + extra_twin + "  model:\n    file: " + test::model_path("scene_wall.xml") + "\n" +
         extra_model;
}

std::string error_of(const std::string& yaml) {
  try {
    parse_twin_config(ConfigNode::load_string(yaml, "twin.yaml"));
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(TwinConfig, ReadsModelMarginsAndPairs) {
  const TwinConfig c = parse_twin_config(ConfigNode::load_string(
      twin_yaml("    safety_margins:\n      spheres: [{name: s, body: link7, pos_m: [0, 0, 0.1], radius_m: 0.05}]\n"
                "      planes: [{name: p, point_m: [0.5, 0, 0], normal: [-1, 0, 0]}]\n"
                "    contact_pairs: [{name: c, a: \"body:link7\", b: \"geom:wall\"}]\n",
                "  mode: lockstep\n  lockstep: {timeout_ms: 200, steps: 10}\n"),
      "twin.yaml"));
  EXPECT_EQ(c.mode, TwinMode::kLockstep);
  EXPECT_DOUBLE_EQ(c.lockstep.timeout_s, 0.2);
  EXPECT_EQ(c.lockstep.steps, 10u);
  ASSERT_EQ(c.model.margin_spheres.size(), 1u);
  EXPECT_DOUBLE_EQ(c.model.margin_spheres[0].radius_m, 0.05);
  ASSERT_EQ(c.model.margin_planes.size(), 1u);
  EXPECT_DOUBLE_EQ(c.model.margin_planes[0].normal[0], -1.0);
  ASSERT_EQ(c.model.contact_pairs.size(), 1u);
  EXPECT_EQ(c.model.contact_pairs[0].b, "geom:wall");
}

TEST(TwinConfig, RejectsAPairSideThatIsNeitherGeomNorBody) {
  const std::string e = error_of(twin_yaml("    contact_pairs: [{name: c, a: \"link7\", b: \"geom:wall\"}]\n"));
  EXPECT_NE(e.find("twin.yaml:"), std::string::npos) << e;
  EXPECT_NE(e.find("twin.model.contact_pairs[0].a"), std::string::npos) << e;
  EXPECT_NE(e.find("'geom:NAME' or 'body:NAME'"), std::string::npos) << e;
}

TEST(TwinConfig, RejectsAZeroPlaneNormalAndAShortVector) {
  EXPECT_NE(error_of(twin_yaml("    safety_margins:\n      planes: [{name: p, point_m: [0, 0, 0], normal: [0, 0, 0]}]\n"))
                .find("normal: must not be zero"),
            std::string::npos);
  EXPECT_NE(error_of(twin_yaml("    safety_margins:\n      spheres: [{name: s, body: b, pos_m: [0, 0], radius_m: 0.1}]\n"))
                .find("pos_m: expected 3 numbers"),
            std::string::npos);
}

TEST(TwinConfig, HilModeNeedsItsGoal) {
  EXPECT_NE(error_of(twin_yaml("", "  mode: hil\n")).find("twin.hil"), std::string::npos);
}

}  // namespace
}  // namespace teleop::twin
