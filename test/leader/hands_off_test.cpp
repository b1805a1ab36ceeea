// Hands off (docs/devices/plugins.md): the operator lets go of a force-feedback device while the
// follower presses on a wall, and the force rendered must not drive the device away. With each
// force-feedback backend: the simulated haptic arm (joints) and the arm of CiA 402 drives as
// master (robot_arm) guarded by their speed, the reference delta plugin (Cartesian) by its
// dead-man button; each against the same device unguarded.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <thread>

#include "emulated_master.h"
#include "following_peer.h"
#include "hands_off_guard.h"
#include "leader_config.h"
#include "leader_node.h"
#include "node_harness.h"
#include "report_counter.h"

namespace teleop::leader {
namespace {

constexpr double kLetGoS = 0.5;

TEST(HandsOffGuard, FasterThanAHandIsLetGoUntilSlowForTheResumeTime) {
  HandsOffGuard guard({0.2, 0.5});
  EXPECT_FALSE(guard.update(0.19, 0));
  EXPECT_TRUE(guard.update(0.21, 1'000'000));
  EXPECT_EQ(guard.events(), 1u);
  EXPECT_TRUE(guard.update(0.09, 2'000'000)) << "slow, not yet for long";
  EXPECT_TRUE(guard.update(0.15, 300'000'000)) << "not below half: the slow time starts again";
  EXPECT_TRUE(guard.update(0.05, 400'000'000));
  EXPECT_FALSE(guard.update(0.05, 900'000'000)) << "slow for 0.5 s: held again";
  EXPECT_EQ(guard.events(), 1u);
  HandsOffGuard off({});
  EXPECT_FALSE(off.update(100.0, 0)) << "infinity: off";
}

// the leader under pfc with `device_keys`, the follower pressing on a wall (the wall pushes its
// flange back with 8 N), the operator letting go at 0.5 s; the device's fastest after that
struct LetGo {
  double peak_speed_mps = 0.0;
  double hands_off_events = 0.0;
  double rendered_at_end = 0.0;
};

LetGo let_go(const std::string& device_keys, const std::string& feedback_keys,
            const DeviceRegistry& devices = builtin_devices()) {
  test::NodeHarness harness{"leader"};
  const ConfigNode root = ConfigNode::load_string(
      "teleoperation: {architecture: pfc}\nleader:\n  joints: 7\n"
      "  home_rad: [0.0, -0.2438, 0.0, -2.1400, 0.0, 3.4638, 0.7854]\n  motion: push_hold\n"
      "  amplitudes_rad: [0, 0, 0, 0, 0, 0, 0]\n  let_go_at_s: " + std::to_string(kLetGoS) + "\n  arm_model: " +
          std::string(TELEOP_SOURCE_DIR) + "/config/models/panda.xml\n" + device_keys +
          "  feedback: {enabled: true, cutoff_hz: 0, max_torque_nm: [20, 20, 20, 20, 5, 5, 5]" + feedback_keys + "}\n",
      "leader.yaml");
  LeaderNode node(parse_leader_config(root, devices), harness.context);
  test::FollowingPeer<msg::CartesianCommand> follower(harness.peer, transport::topics::kLeaderCartesian, 7);
  transport::Publication<msg::WrenchStamped> wrench(harness.peer, transport::topics::kFollowerWrench, "follower");
  EXPECT_TRUE(test::eventually([&] { return follower.state.matched() > 0 && follower.command.reader().matched() > 0; }));
  LetGo seen;
  const auto period = std::chrono::milliseconds(1);
  auto next = std::chrono::steady_clock::now();
  for (int i = 0; i < 1500; ++i) {
    EXPECT_TRUE(follower.publish());
    wrench.sample().force_n().x(-8.0);
    EXPECT_TRUE(wrench.publish());
    next += period;
    std::this_thread::sleep_until(next);
    node.cycle(harness.tick());
    if (i * 1e-3 > kLetGoS) seen.peak_speed_mps = std::max(seen.peak_speed_mps, node.device_speed_mps());
  }
  runtime::NodeReport report;
  node.fill_report(report);
  seen.hands_off_events = test::counter(report, "hands_off_events");
  seen.rendered_at_end = std::abs(node.rendered_torque()[0]) + std::abs(node.rendered_torque()[1]) +
                         std::abs(node.rendered_torque()[2]);
  return seen;
}

TEST(HandsOff, AHapticArmLetGoInContactIsStoppedByItsSpeedGuard) {
  const std::string arm = "  device: haptic_arm\n  haptic_arm: {model: " + std::string(TELEOP_SOURCE_DIR) +
                          "/config/models/panda.xml}\n";
  const LetGo unguarded = let_go(arm, "");
  const LetGo guarded = let_go(arm, ", hands_off_speed_mps: 0.1");
  std::printf("haptic arm let go in contact: fastest %.3f m/s unguarded, %.3f m/s guarded\n", unguarded.peak_speed_mps,
              guarded.peak_speed_mps);
  EXPECT_EQ(unguarded.hands_off_events, 0.0);
  EXPECT_GE(guarded.hands_off_events, 1.0);
  EXPECT_LT(guarded.peak_speed_mps, 0.5 * unguarded.peak_speed_mps) << "the force stopped driving it away";
}

// the arm of CiA 402 drives as master (in process): no hand on it at all, so let go from the start
TEST(HandsOff, ACanArmMasterLetGoInContactIsStoppedByItsSpeedGuard) {
  const std::string arm = test::emulated_master_keys();
  const LetGo unguarded = let_go(arm, "", test::emulated_master_devices());
  const LetGo guarded = let_go(arm, ", hands_off_speed_mps: 0.1", test::emulated_master_devices());
  std::printf("CAN arm master let go in contact: fastest %.3f m/s unguarded, %.3f m/s guarded\n",
              unguarded.peak_speed_mps, guarded.peak_speed_mps);
  EXPECT_EQ(unguarded.hands_off_events, 0.0);
  EXPECT_GE(guarded.hands_off_events, 1.0);
  EXPECT_LT(guarded.peak_speed_mps, 0.5 * unguarded.peak_speed_mps) << "the force stopped driving it away";
}

TEST(HandsOff, ADeltaPluginLetGoInContactLosesItsForceWithItsDeadMan) {
  // in the leader's process, so that the delta's hand (which counts its time in its reads) lets
  // go at the leader's cycle of let_go_at_s
  const std::string delta = std::string("  device: plugin\n  plugin: {library: ") + TELEOP_DELTA_PLUGIN +
                            ", isolation: in_process, settings: {frequency_hz: 0, mass_kg: 0.3, let_go_at_s: " + std::to_string(kLetGoS) + "}}\n";
  const LetGo unguarded = let_go(delta, "");
  const LetGo guarded = let_go(delta + "  buttons: {dead_man: 0}\n", "");
  std::printf("delta let go in contact: fastest %.3f m/s without a dead-man, %.3f m/s with\n", unguarded.peak_speed_mps,
              guarded.peak_speed_mps);
  EXPECT_LT(guarded.peak_speed_mps, 0.5 * unguarded.peak_speed_mps) << "the force stopped driving it away";
  EXPECT_LT(guarded.rendered_at_end, 1e-9) << "nothing rendered on a device let go";
  EXPECT_GT(unguarded.rendered_at_end, 1.0);
}

}  // namespace
}  // namespace teleop::leader
