// The device's stop-chain buttons in the leader's configuration (leader.buttons) and the simulated
// operator pressing them (leader.button_presses).
#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <thread>

#include "button_input.h"
#include "leader_config.h"
#include "node_harness.h"
#include "operator_motion.h"
#include "report_counter.h"
#include "teleop/leader/leader_arms.h"
#include "teleop/leader/simulated_devices.h"

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

// a press held 50 ms sends one stop (repeats come every 100 ms while held), and none once released:
// a device whose read() leaves the button word alone must not keep the press for ever
TEST(StopButtons, APressEndsWithItsHold) {
  const ConfigNode root = shipped_leader_with(
      {"leader.buttons={emergency_stop: 3}", "leader.button_presses=[{button: 3, at_s: 0.01, hold_s: 0.05}]"});
  DeviceRegistry devices;
  add_simulated_devices(devices);
  const runtime::LogicBuilder build = leader_logic_parser(devices)(root);
  test::NodeHarness harness{"leader"};
  const std::unique_ptr<runtime::NodeLogic> node = build(harness.context);
  for (int i = 0; i < 400; ++i) {
    node->cycle(harness.tick());
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  runtime::NodeReport report;
  node->fill_report(report);
  EXPECT_EQ(test::counter(report, "emergency_stops_sent"), 1.0);
}

TEST(ButtonInputConfig, KeysAreTheKernelsNamesMappedToButtons) {
  const LeaderConfig c = parse_leader_config(shipped_leader_with(
      {"leader.button_input={device: \"Pedal Co. USB Foot Switch\", keys: {KEY_PAUSE: 0, BTN_0: 5}}"}));
  ASSERT_TRUE(c.button_input.has_value());
  EXPECT_EQ(c.button_input->device, "Pedal Co. USB Foot Switch");
  ASSERT_EQ(c.button_input->keys.size(), 2u);
  EXPECT_EQ(c.button_input->keys[0], (std::pair<unsigned, int>{119u, 0}));   // KEY_PAUSE
  EXPECT_EQ(c.button_input->keys[1], (std::pair<unsigned, int>{0x100u, 5}));  // BTN_0
}

TEST(ButtonInputConfig, AnUnknownKeyOrAButtonBeyondTheWordIsNamed) {
  try {
    (void)parse_leader_config(shipped_leader_with({"leader.button_input={device: /dev/input/event9, keys: {KEY_PAWS: 0}}"}));
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("KEY_PAWS"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("not a key the kernel knows"), std::string::npos) << e.what();
  }
  EXPECT_THROW((void)parse_leader_config(shipped_leader_with({"leader.button_input={device: x, keys: {BTN_0: 32}}"})),
               ConfigError);
  EXPECT_THROW((void)parse_leader_config(shipped_leader_with({"leader.button_input={device: x, keys: {}}"})), ConfigError);
}

TEST(ButtonInputConfig, ADeviceThatIsNotThereStopsTheStartNamingIt) {
  try {
    ButtonInput input({"/dev/input/no-such-button", {{119u, 0}}}, 1u);
    FAIL() << "opened";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "leader.button_input: no input device /dev/input/no-such-button");
  }
}

}  // namespace
}  // namespace teleop::leader
