// The `teleoperation:` section (teleoperation/architecture.h): which architecture runs and the
// settings of its TDPA ends.
#include "teleop/runtime/architecture.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <string_view>
#include <vector>

namespace teleop::runtime {
namespace {

std::optional<TeleoperationConfig> parse(const std::string& text) {
  return parse_teleoperation_config(ConfigNode::load_string(text, "node.yaml"));
}

std::string error_of(const std::string& text) {
  try {
    (void)parse(text);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(TeleoperationConfig, IsAbsentWithoutTheSection) { EXPECT_FALSE(parse("node: {name: x}\n").has_value()); }

TEST(TeleoperationConfig, ReadsEachArchitectureByName) {
  EXPECT_EQ(parse("teleoperation: {architecture: position_position}\n")->architecture,
            find_architecture("position_position"));
  EXPECT_EQ(parse("teleoperation: {architecture: pfc}\n")->architecture, find_architecture("pfc"));
  EXPECT_EQ(parse("teleoperation: {architecture: pfc_tdpa}\n")->architecture, find_architecture("pfc_tdpa"));
  EXPECT_EQ(parse("teleoperation: {architecture: mmt}\n")->architecture, find_architecture("mmt"));
  EXPECT_EQ(find_architecture("pfc_tdpa")->name, "pfc_tdpa");
}

TEST(TeleoperationConfig, DefaultsToUnlimitedDampersAndNoDriftCompensation) {
  const auto c = parse("teleoperation: {architecture: pfc_tdpa}\n");
  EXPECT_TRUE(std::isinf(c->tdpa.max_leader_damping));
  EXPECT_TRUE(std::isinf(c->tdpa.max_follower_damping));
  EXPECT_EQ(c->tdpa.drift_time_constant_s, 0.0);
}

TEST(TeleoperationConfig, ReadsTheTdpaSettings) {
  const auto c = parse(
      "teleoperation:\n  architecture: pfc_tdpa\n  tdpa:\n    max_leader_damping: 0\n    max_follower_damping: 0.5\n"
      "    drift_time_constant_s: 0.4\n    drift_max_speed_m_per_s: 0.03\n    drift_max_speed_rad_per_s: 0.1\n"
      "    drift_contact_force_n: 4\n    drift_contact_torque_nm: 0.8\n");
  EXPECT_TRUE(std::isinf(c->tdpa.max_leader_damping));  // 0 in the file: no limit
  EXPECT_EQ(c->tdpa.max_follower_damping, 0.5);
  EXPECT_EQ(c->tdpa.drift_time_constant_s, 0.4);
  EXPECT_EQ(c->tdpa.drift_max_speed_m_per_s, 0.03);
  EXPECT_EQ(c->tdpa.drift_max_speed_rad_per_s, 0.1);
  EXPECT_EQ(c->tdpa.drift_contact_force_n, 4.0);
  EXPECT_EQ(c->tdpa.drift_contact_torque_nm, 0.8);
}

TEST(TeleoperationConfig, NamesFileAndKeyOfABadValue) {
  const std::string unknown = error_of("teleoperation: {architecture: bilateral}\n");
  EXPECT_NE(unknown.find("node.yaml"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("teleoperation.architecture"), std::string::npos) << unknown;
  const std::string negative = error_of("teleoperation: {architecture: pfc_tdpa, tdpa: {drift_time_constant_s: -1}}\n");
  EXPECT_NE(negative.find("teleoperation.tdpa.drift_time_constant_s"), std::string::npos) << negative;
  const std::string zero = error_of("teleoperation: {architecture: pfc_tdpa, tdpa: {drift_max_speed_m_per_s: 0}}\n");
  EXPECT_NE(zero.find("teleoperation.tdpa.drift_max_speed_m_per_s"), std::string::npos) << zero;
}

// the registry (runtime/architecture.h): the built-ins, the default first, and what the follower
// and the twin play their part from
TEST(ArchitectureRegistry, HoldsTheFourBuiltInsWithTheDefaultFirst) {
  std::vector<std::string_view> names;
  for (const Architecture& a : architectures()) names.push_back(a.name);
  EXPECT_EQ(names, (std::vector<std::string_view>{"position_position", "pfc", "pfc_tdpa", "mmt"}));
  EXPECT_EQ(TeleoperationConfig{}.architecture, find_architecture("position_position"));
  EXPECT_EQ(find_architecture("bilateral"), nullptr);
}

TEST(ArchitectureRegistry, SaysWhoCommandsTheFollowerAndWhetherTdpaCorrects) {
  EXPECT_EQ(find_architecture("position_position")->commands, CommandPath::kLeaderJoint);
  EXPECT_TRUE(is_cartesian(*find_architecture("pfc")));
  EXPECT_TRUE(is_cartesian(*find_architecture("pfc_tdpa")));
  EXPECT_FALSE(is_cartesian(*find_architecture("mmt")));
  EXPECT_EQ(find_architecture("mmt")->commands, CommandPath::kTwin);
  for (const Architecture& a : architectures()) EXPECT_EQ(a.tdpa_corrects, a.name == "pfc_tdpa") << a.name;
}

TEST(ArchitectureRegistry, AnUnknownNameListsTheRegisteredOnes) {
  const std::string unknown = error_of("teleoperation: {architecture: bilateral}\n");
  EXPECT_NE(unknown.find("'bilateral' is not one of: position_position, pfc, pfc_tdpa, mmt"), std::string::npos)
      << unknown;
}

}  // namespace
}  // namespace teleop::runtime
