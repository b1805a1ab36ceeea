// The device's stop-chain buttons in the leader's configuration (leader.buttons) and the simulated
// operator pressing them (leader.button_presses).
#include <gtest/gtest.h>

#include <string>

#include "leader_config.h"
#include "operator_motion.h"

namespace teleop::leader {
namespace {

ConfigNode shipped_leader_with(const std::vector<std::string>& overrides) {
  ConfigNode root = ConfigNode::load_file(std::string(TELEOP_SOURCE_DIR) + "/config/nodes/leader.yaml");
  for (const std::string& o : overrides) root.apply_override(o);
  return root;
}

TEST(StopButtons, NoneUnlessConfigured) {
  const LeaderConfig c = parse_leader_config(shipped_leader_with({}));
  EXPECT_EQ(c.stop_buttons.emergency_stop, -1);
  EXPECT_EQ(c.stop_buttons.enable, -1);
  EXPECT_TRUE(c.motion.presses.empty());
}

TEST(StopButtons, ReadsTheButtonsAndThePresses) {
  const LeaderConfig c = parse_leader_config(shipped_leader_with(
      {"leader.buttons={emergency_stop: 3, enable: 4}", "leader.button_presses=[{button: 3, at_s: 2.0, hold_s: 0.5}]"}));
  EXPECT_EQ(c.stop_buttons.emergency_stop, 3);
  EXPECT_EQ(c.stop_buttons.enable, 4);
  const OperatorMotion motion(c.motion);
  EXPECT_EQ(motion.pressed_buttons(1.999), 0u);
  EXPECT_EQ(motion.pressed_buttons(2.0), 1u << 3);
  EXPECT_EQ(motion.pressed_buttons(2.499), 1u << 3);
  EXPECT_EQ(motion.pressed_buttons(2.5), 0u);
}

TEST(StopButtons, AnEnableOnTheStopsButtonIsRefusedNamingTheKey) {
  try {
    (void)parse_leader_config(shipped_leader_with({"leader.buttons={emergency_stop: 1, enable: 1}"}));
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("leader.buttons.enable"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("deliberate other act"), std::string::npos) << e.what();
  }
}

TEST(StopButtons, AButtonBeyondTheDevicesWordIsRefused) {
  EXPECT_THROW((void)parse_leader_config(shipped_leader_with({"leader.buttons={emergency_stop: 32}"})), ConfigError);
  EXPECT_THROW((void)parse_leader_config(shipped_leader_with({"leader.button_presses=[{button: 0}]"})), ConfigError)
      << "a press needs its time";
}

}  // namespace
}  // namespace teleop::leader
