// A vendor's device behind the plugin interface (teleop/leader/teleop_device_v1.h), driven through
// the reference plugin (leader/plugins/simulated_delta.c): its handle moves where the simulated
// hand takes it and gives way to the force rendered, efforts stay within the limits it declared,
// a failing or NaN-measuring plugin fails the read (the leader holds), and a library that is not
// a plugin, or of another interface, is refused naming it.
#include "plugin_device.h"

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <thread>

#include "following_peer.h"
#include "leader_config.h"
#include "leader_node.h"
#include "node_harness.h"
#include "report_counter.h"
#include "test_helpers.h"

namespace teleop::leader {
namespace {

constexpr double kPeriod = 1e-3;

std::shared_ptr<const PluginLibrary> delta() { return std::make_shared<const PluginLibrary>(TELEOP_DELTA_PLUGIN); }

// n periods of reads (and the same force written before each), the last state
DeviceState run(PluginDevice& device, int n, double force_x_n = 0.0) {
  DeviceState state;
  JointVector force{};
  force[0] = force_x_n;
  for (int i = 0; i < n; ++i) {
    EXPECT_TRUE(device.write(force));
    EXPECT_TRUE(device.read(state));
  }
  return state;
}

TEST(PluginDevice, TheReferenceDeltaMovesWithTheHandAndGivesWayToTheForceRendered) {
  const auto library = delta();
  EXPECT_TRUE(library->cartesian());
  PluginDevice device(library, {{"reach_x_m", "0.03"}, {"ramp_s", "0.5"}, {"frequency_hz", "0"}}, kPeriod, 7);
  EXPECT_STREQ(device.name(), "simulated delta");
  EXPECT_EQ(device.joints(), 0u);
  DeviceState state = run(device, 3000);
  EXPECT_NEAR(state.position_m[0], 0.03, 1e-4) << "where the hand took it";
  EXPECT_EQ(state.buttons, 1u) << "the hand holds its button 0";
  // pushed back by 4 N: the hand's spring (400 N/m) gives way by 1 cm
  state = run(device, 3000, -4.0);
  EXPECT_NEAR(state.position_m[0], 0.03 - 4.0 / 400.0, 1e-4);
  EXPECT_EQ(device.limited_efforts(), 0u);
}

TEST(PluginDevice, EffortsStayWithinTheLimitTheDeviceDeclared) {
  PluginDevice device(delta(), {{"max_force_n", "5"}, {"frequency_hz", "0"}}, kPeriod, 7);
  const DeviceState state = run(device, 3000, 50.0);
  EXPECT_NEAR(state.position_m[0], 5.0 / 400.0, 1e-4) << "5 N rendered, not 50";
  EXPECT_EQ(device.limited_efforts(), 3000u);
}

TEST(PluginDevice, AFailingOrNanMeasuringPluginFailsTheReadAndIsCounted) {
  PluginDevice failing(delta(), {{"fail_after_reads", "10"}}, kPeriod, 7);
  DeviceState state;
  for (int i = 0; i < 10; ++i) ASSERT_TRUE(failing.read(state));
  EXPECT_FALSE(failing.read(state));
  EXPECT_EQ(failing.failed_reads(), 1u);
  PluginDevice poisoned(delta(), {{"nan_after_reads", "5"}}, kPeriod, 7);
  for (int i = 0; i < 5; ++i) ASSERT_TRUE(poisoned.read(state));
  EXPECT_FALSE(poisoned.read(state));
  EXPECT_EQ(poisoned.invalid_reads(), 1u);
  EXPECT_TRUE(std::isfinite(state.position_m[0])) << "nothing not finite reaches the leader";
}

TEST(PluginDevice, ThePluginsOwnRefusalsAndForeignLibrariesAreNamed) {
  EXPECT_EQ(test::error_of<std::runtime_error>([] { PluginDevice(delta(), {{"stiffnes", "3"}}, kPeriod, 7); }),
            std::string("leader.plugin: ") + TELEOP_DELTA_PLUGIN + ": unknown setting stiffnes");
  EXPECT_NE(test::error_of<std::runtime_error>([] { PluginDevice(delta(), {{"mass_kg", "heavy"}}, kPeriod, 7); })
                .find("setting mass_kg: 'heavy' is not a number"),
            std::string::npos);
  EXPECT_NE(test::error_of<std::runtime_error>([] { PluginLibrary("libm.so.6"); })
                .find("libm.so.6 exports no teleop_device_v1_entry: not a teleop device plugin"),
            std::string::npos);
  EXPECT_NE(test::error_of<std::runtime_error>([] { PluginLibrary(TELEOP_OTHER_ABI_PLUGIN); })
                .find("speaks teleop_device ABI 2, not 1"),
            std::string::npos);
  EXPECT_NE(test::error_of<std::runtime_error>([] { PluginLibrary("/nonexistent/libx.so"); }).find("cannot load"),
            std::string::npos);
}

ConfigNode leader_yaml(const std::string& architecture, const std::string& plugin) {
  return ConfigNode::load_string("teleoperation: {architecture: " + architecture +
                                     "}\nleader:\n  joints: 7\n  feedback: {enabled: true, max_torque_nm: [20, 20, 20, 2, 2, 2, 2]}\n"
                                     "  home_rad: [0.0, -0.2438, 0.0, -2.2, 0.0, 1.96, 0.785]\n  arm_model: " +
                                     std::string(TELEOP_SOURCE_DIR) + "/config/models/panda.xml\n  device: plugin\n  plugin: " +
                                     plugin + "\n",
                                 "leader.yaml");
}

TEST(PluginDevice, TheConfigurationLoadsTheLibraryAndNamesWhatIsWrong) {
  const std::string library = std::string("{library: ") + TELEOP_DELTA_PLUGIN + ", settings: {reach_x_m: 0.02}}";
  EXPECT_TRUE(parse_leader_config(leader_yaml("pfc", library)).device->cartesian());
  EXPECT_NE(test::error_of<ConfigError>([&] { parse_leader_config(leader_yaml("position_position", library)); })
                .find("leader.device: plugin moves a Cartesian pose"),
            std::string::npos);
  EXPECT_NE(test::error_of<ConfigError>([] { parse_leader_config(leader_yaml("pfc", "{library: ./no_such_plugin.so}")); })
                .find("leader.plugin.library: no file"),
            std::string::npos);
  EXPECT_NE(test::error_of<ConfigError>([] { parse_leader_config(leader_yaml("pfc", "{library: libm.so.6}")); })
                .find("leader.plugin.library: libm.so.6 exports no teleop_device_v1_entry"),
            std::string::npos);
}

// the leader under pfc with the delta: the hand's reach moves the command, the follower's force
// is rendered on the handle; a plugin that fails holds the leader, with its fault on the bus
TEST(PluginDevice, TheLeaderCommandsFromThePluginRendersOnItAndHoldsWhenItFails) {
  test::NodeHarness harness{"leader"};
  const std::string settings = std::string("{library: ") + TELEOP_DELTA_PLUGIN +
                               ", isolation: in_process, settings: {reach_z_m: 0.02, ramp_s: 0.2, frequency_hz: 0, fail_after_reads: 400}}";
  LeaderNode node(parse_leader_config(leader_yaml("pfc", settings)), harness.context);
  test::FollowingPeer<msg::CartesianCommand> follower(harness.peer, transport::topics::kLeaderCartesian, 7);
  transport::Publication<msg::WrenchStamped> wrench(harness.peer, transport::topics::kFollowerWrench, "follower");
  ASSERT_TRUE(test::eventually([&] { return follower.state.matched() > 0 && follower.command.reader().matched() > 0; }));
  double start_z = std::nan("");
  double reached_z = 0.0;
  for (int i = 0; i < 400 && node.state() != msg::STATE_SAFE_HOLD; ++i) {
    ASSERT_TRUE(follower.publish());
    wrench.sample().force_n().x(-3.0);  // the follower pushes back along x
    ASSERT_TRUE(wrench.publish());
    std::this_thread::sleep_for(std::chrono::microseconds(500));
    node.cycle(harness.tick());
    follower.command.poll();
    if (!follower.command.has_sample()) continue;
    const double z = follower.command.latest().target_pose().position_m().z();
    if (std::isnan(start_z)) start_z = z;
    reached_z = z;
  }
  EXPECT_GT(reached_z - start_z, 0.01) << "the hand lifted the handle, the command followed";
  EXPECT_NEAR(node.rendered_torque()[0], -3.0, 0.5) << "the follower's push rendered as a force on the handle";
  // the plugin failed at its 400th read: the leader holds
  for (int i = 0; i < 50 && node.state() != msg::STATE_SAFE_HOLD; ++i) {
    ASSERT_TRUE(follower.publish());
    node.cycle(harness.tick());
  }
  EXPECT_EQ(node.state(), msg::STATE_SAFE_HOLD);
  std::vector<uint32_t> faults;
  node.active_faults(faults);
  EXPECT_EQ(faults, std::vector<uint32_t>{msg::FAULT_HARDWARE});
  runtime::NodeReport report;
  node.fill_report(report);
  EXPECT_GE(test::counter(report, "plugin_failed_reads"), 1.0) << "the plugin's own counters in the node's report";
  EXPECT_EQ(test::counter(report, "plugin_invalid_reads"), 0.0);
}

}  // namespace
}  // namespace teleop::leader
