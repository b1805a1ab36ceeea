// The 6-DoF mouse and the gamepad in a leader's configuration (leader.device: spacemouse,
// gamepad; teleop/leader/input_devices.h): what they read and the errors that name the key. The
// devices themselves are driven through the kernel's uinput in the VM (test/vcan/input_device_vm_test.cpp).
#include "teleop/leader/input_devices.h"

#include <gtest/gtest.h>

#include <string>

#include "leader_config.h"
#include "teleop/leader/simulated_devices.h"
#include "test_helpers.h"

namespace teleop::leader {
namespace {

DeviceRegistry devices() {
  DeviceRegistry r;
  add_simulated_devices(r);
  add_input_devices(r);
  return r;
}

// a leader of the given architecture with the given keys added to its section
ConfigNode leader_yaml(const std::string& architecture, const std::string& keys) {
  return ConfigNode::load_string("teleoperation: {architecture: " + architecture + "}\nleader:\n  joints: 7\n  feedback: {enabled: false}\n  arm_model: " +
                                     std::string(TELEOP_SOURCE_DIR) + "/config/models/panda.xml\n" + keys,
                                 "leader.yaml");
}

LeaderConfig parse(const std::string& architecture, const std::string& keys) {
  return parse_leader_config(leader_yaml(architecture, keys), devices());
}

std::string refusal(const std::string& architecture, const std::string& keys) {
  return test::error_of<ConfigError>([&] { parse(architecture, keys); });
}

TEST(InputDevices, ASpaceMouseAndAGamepadAreCartesianDevicesOfTheRegistry) {
  const LeaderConfig mouse = parse("pfc", "  device: spacemouse\n  spacemouse: {device: \"046d:c626\"}\n");
  EXPECT_STREQ(mouse.device->device(), "spacemouse");
  EXPECT_TRUE(mouse.device->cartesian());
  const LeaderConfig pad = parse("pfc_tdpa", "  device: gamepad\n  gamepad: {device: /dev/input/js0, dead_band: 0.2}\n");
  EXPECT_STREQ(pad.device->device(), "gamepad");
  EXPECT_TRUE(pad.device->cartesian());
  EXPECT_FALSE(parse("pfc", "").device->cartesian()) << "the script moves joints";
}

TEST(InputDevices, AnArchitectureThatNeedsJointsRefusesThemNamingBoth) {
  EXPECT_EQ(refusal("position_position", "  device: spacemouse\n  spacemouse: {device: x}\n"),
            "leader.yaml:6: leader.device: spacemouse moves a Cartesian pose, it has no joints: architecture "
            "position_position commands joint positions; use pfc or pfc_tdpa");
  EXPECT_NE(refusal("mmt", "  device: gamepad\n  gamepad: {device: x}\n").find("architecture mmt"), std::string::npos);
}

TEST(InputDevices, AnAxisOrKeyTheKernelDoesNotKnowOrABadTargetIsNamed) {
  EXPECT_NE(refusal("pfc", "  device: spacemouse\n  spacemouse: {device: x, axes: {REL_Q: x}}\n")
                .find("leader.spacemouse.axes.REL_Q: is not an axis the kernel knows"),
            std::string::npos);
  EXPECT_NE(refusal("pfc", "  device: spacemouse\n  spacemouse: {device: x, axes: {ABS_X: w}}\n")
                .find("leader.spacemouse.axes.ABS_X: drives 'w': give one of x y z rx ry rz"),
            std::string::npos);
  EXPECT_NE(refusal("pfc", "  device: gamepad\n  gamepad: {device: x, keys: {BTN_NOPE: 0}}\n")
                .find("leader.gamepad.keys.BTN_NOPE: is not a key the kernel knows"),
            std::string::npos);
  EXPECT_NE(refusal("pfc", "  device: gamepad\n  gamepad: {keys: {BTN_TR: 0}}\n").find("leader.gamepad.device"),
            std::string::npos)
      << "the device to open is required";
}

TEST(InputDevices, TheDeadManTheClutchAndTheWorkspaceBoxAreCheckedButtons) {
  const LeaderConfig c = parse("pfc", "  buttons: {dead_man: 0, clutch: 1}\n"
                                      "  workspace_box_m: {min: [0.2, -0.4, 0.1], max: [0.8, 0.4, 0.9]}\n");
  EXPECT_EQ(c.stop_buttons.dead_man, 0);
  EXPECT_EQ(c.stop_buttons.clutch, 1);
  ASSERT_TRUE(c.workspace_box);
  EXPECT_EQ(c.workspace_box->max_m[2], 0.9);
  EXPECT_NE(refusal("pfc", "  buttons: {dead_man: 0, clutch: 0}\n").find("leader.buttons.clutch: is the dead-man button too"),
            std::string::npos);
  EXPECT_NE(refusal("pfc", "  buttons: {emergency_stop: 2, dead_man: 2}\n")
                .find("leader.buttons.dead_man: is a button of the stop chain too"),
            std::string::npos);
  EXPECT_NE(refusal("pfc", "  workspace_box_m: {min: [0, 0, 0], max: [1, -1, 1]}\n")
                .find("leader.workspace_box_m.max: must exceed min"),
            std::string::npos);
}

}  // namespace
}  // namespace teleop::leader
