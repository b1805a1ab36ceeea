// The twin's configuration: errors name file, key and problem.
#include "twin_config.h"

#include <gtest/gtest.h>

#include "twin_test_util.h"

namespace teleop::twin {
namespace {

std::string twin_yaml(const std::string& extra_model, const std::string& extra_twin = "") {
  return "twin:\n  joints: 7\n" + extra_twin + "  model:\n    file: " + test::model_path("scene_wall.xml") + "\n" +
         extra_model;
}

std::string error_of(const std::string& yaml) { return test::config_error(parse_twin_config, yaml, "twin.yaml"); }

TEST(TwinConfig, ReadsModelMarginsAndPairs) {
  const TwinConfig c = parse_twin_config(ConfigNode::load_string(
      twin_yaml("    safety_margins:\n      activation_m: 0.02\n"
                "      spheres: [{name: s, body: link7, pos_m: [0, 0, 0.1], radius_m: 0.05}]\n"
                "      planes: [{name: p, point_m: [0.5, 0, 0], normal: [-1, 0, 0]}]\n"
                "    contact_pairs: [{name: c, a: \"body:link7\", b: \"geom:wall\"}]\n",
                "  mode: lockstep\n  lockstep: {timeout_ms: 200, steps: 10}\n"),
      "twin.yaml"));
  EXPECT_EQ(c.mode, TwinMode::kLockstep);
  EXPECT_DOUBLE_EQ(c.lockstep.timeout_s, 0.2);
  EXPECT_EQ(c.lockstep.steps, 10u);
  ASSERT_EQ(c.model.margin_spheres.size(), 1u);
  EXPECT_DOUBLE_EQ(c.model.margin_spheres[0].radius_m, 0.05);
  EXPECT_DOUBLE_EQ(c.model.margin_activation_m, 0.02);
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

TEST(TwinConfig, ReadsTheMmtCorrectionAndTheModelsGeomOffsets) {
  const TwinConfig c = parse_twin_config(ConfigNode::load_string(
      twin_yaml("    geom_offsets: [{geom: wall, offset_m: [0.02, 0, 0]}]\n",
                "  mmt:\n    correction: {geom: wall, normal: [-0.5, 0, 0], rate_m_per_s: 0.01, timeout_ms: 50}\n"),
      "twin.yaml"));
  ASSERT_EQ(c.model.geom_offsets.size(), 1u);
  EXPECT_EQ(c.model.geom_offsets[0].geom, "wall");
  EXPECT_DOUBLE_EQ(c.model.geom_offsets[0].offset_m[0], 0.02);
  ASSERT_TRUE(c.mmt.correction.has_value());
  EXPECT_EQ(c.mmt.correction->geom, "wall");
  EXPECT_DOUBLE_EQ(c.mmt.correction->normal[0], -1.0) << "scaled to unit length";
  EXPECT_DOUBLE_EQ(c.mmt.correction->rate_m_per_s, 0.01);
  EXPECT_DOUBLE_EQ(c.mmt.correction->timeout_s, 0.05);
  EXPECT_FALSE(parse_twin_config(ConfigNode::load_string(twin_yaml(""), "twin.yaml")).mmt.correction.has_value())
      << "absent: no correction";
}

TEST(TwinConfig, RejectsAnInconsistentCorrection) {
  const auto correction = [](const std::string& body) { return "  mmt:\n    correction: {" + body + "}\n"; };
  std::string e = error_of(twin_yaml("", correction("geom: wall, normal: [0, 0, 0]")));
  EXPECT_NE(e.find("twin.mmt.correction.normal: must not be zero"), std::string::npos) << e;
  e = error_of(twin_yaml("", correction("geom: wall, normal: [-1, 0, 0], contact_force_n: 2, free_force_n: 3")));
  EXPECT_NE(e.find("twin.mmt.correction.free_force_n: must not exceed contact_force_n"), std::string::npos) << e;
  e = error_of(twin_yaml("", correction("geom: wall, normal: [-1, 0, 0], probe: link7")));
  EXPECT_NE(e.find("twin.mmt.correction.probe"), std::string::npos) << e;
  e = error_of(twin_yaml("", correction("normal: [-1, 0, 0]")));
  EXPECT_NE(e.find("twin.mmt.correction.geom"), std::string::npos) << e;
}

}  // namespace
}  // namespace teleop::twin
