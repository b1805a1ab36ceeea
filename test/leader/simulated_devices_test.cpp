// The devices every build has behind the registry: each shipped leader config reads as before
// (every key used, the same device), a file switches device by --set, and what each spec builds.
#include "teleop/leader/simulated_devices.h"

#include <gtest/gtest.h>

#include <string>

#include "leader_config.h"
#include "teleop/runtime/node_config.h"
#include "teleop/transport/participant_config.h"
#include "test_helpers.h"

namespace teleop::leader {
namespace {

ConfigNode shipped(const std::string& name) {
  return ConfigNode::load_file(std::string(TELEOP_SOURCE_DIR) + "/config/nodes/" + name + ".yaml");
}

// what run_node reads of a leader's file, then "every key read"; the first hand's config
LeaderConfig read_like_the_leader(const ConfigNode& root) {
  runtime::parse_node_config(root.child("node"), "leader");
  transport::parse_participant_config(root.child("transport"), "leader");
  const auto arms = parse_leader_arms(root);
  root.check_all_used();
  return arms.front();
}

TEST(SimulatedDevices, EveryShippedLeaderConfigReadsWithTheSameDevice) {
  for (const auto& [name, device] :
       {std::pair{"leader", "scripted"}, std::pair{"leader_hand", "scripted"},
        std::pair{"leader_haptic_arm", "haptic_arm"}, std::pair{"leader_stiff_wall", "haptic_arm"},
        std::pair{"leader_box_task", "haptic_arm"}}) {
    EXPECT_STREQ(read_like_the_leader(shipped(name)).device->device(), device) << name;
  }
}

TEST(SimulatedDevices, AFileKeepingTheHapticArmsSettingsSwitchesToItBySet) {
  ConfigNode root = shipped("leader");
  root.apply_override("leader.device=haptic_arm");
  EXPECT_STREQ(read_like_the_leader(root).device->device(), "haptic_arm");
}

TEST(SimulatedDevices, TheHapticArmsOfATwoHandedStationAreEachHandsModel) {
  const ConfigNode root = shipped("leader_box_task");
  for (const LeaderConfig& hand : parse_leader_arms(root)) {
    const auto device = hand.device->make({1e-3, hand.joints, hand.home_rad, hand.arm_model});
    EXPECT_STREQ(device->name(), "simulated_haptic_arm") << hand.arm;
    EXPECT_EQ(device->joints(), 7u) << hand.arm;
    EXPECT_NE(hand.arm_model.find(hand.arm + "_arm.xml"), std::string::npos) << hand.arm;
  }
}

TEST(SimulatedDevices, TheHapticArmNeedsItsSection) {
  const std::string refusal = test::error_of<ConfigError>([] {
    simulated_devices().parse(
        ConfigNode::load_string("leader:\n  joints: 7\n  device: haptic_arm\n", "leader.yaml").child("leader"));
  });
  EXPECT_NE(refusal.find("leader.haptic_arm: device: haptic_arm needs a haptic_arm section with the model file"),
            std::string::npos)
      << refusal;
}

TEST(SimulatedDevices, EachSpecBuildsItsDeviceForTheLeadersSetup) {
  const test::TempDir dir("simulated_devices_test");
  const std::string recording = dir.write("run.csv", "t_s,q_dev_0,q_dev_1\n0,0.1,0.2\n1,0.3,0.4\n");
  const ConfigNode replay = ConfigNode::load_string(
      "leader:\n  joints: 2\n  device: replay\n  replay: {file: " + recording + "}\n", "leader.yaml");
  DeviceSetup setup;
  setup.joints = 2;
  const auto played = simulated_devices().parse(replay.child("leader"))->make(setup);
  EXPECT_STREQ(played->name(), "replay");
  EXPECT_EQ(played->joints(), 2u);

  const auto scripted = simulated_devices()
                            .parse(ConfigNode::load_string("leader:\n  joints: 2\n", "leader.yaml").child("leader"))
                            ->make(setup);
  OperatorIntent intent;
  intent.q_rad[1] = 0.7;
  scripted->set_operator_intent(intent);
  DeviceState state;
  ASSERT_TRUE(scripted->read(state));
  EXPECT_EQ(state.q_rad[1], 0.7) << "the scripted device is where the operator wants it";
  EXPECT_EQ(scripted->joints(), 2u);
}

}  // namespace
}  // namespace teleop::leader
