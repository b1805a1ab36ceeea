// A device plugin in a process of its own (leader.plugin.isolation: process,
// isolated_plugin_device.h): the reference delta served by teleop_device_host through the shared
// memory, its handle moving with the hand and giving way to the force rendered; a plugin that
// crashes (SIGSEGV in its read) or a host killed takes only the host down: the leader's reads fail
// within the host's timeout and the leader holds, on the bus, and goes on; a host that cannot open
// the device names the plugin's error. The sequence lock of the channel, torn reads refused.
#include "isolated_plugin_device.h"

#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <string>
#include <thread>

#include "following_peer.h"
#include "leader_config.h"
#include "leader_node.h"
#include "node_harness.h"
#include "report_counter.h"

namespace teleop::leader {
namespace {

using namespace std::chrono_literals;

// the host's timeout long enough for a loaded test machine to starve the host a while
HostedPluginConfig delta(PluginSettings settings, double host_timeout_s = 1.0) {
  HostedPluginConfig c;
  c.library = TELEOP_DELTA_PLUGIN;
  c.settings = std::move(settings);
  c.cartesian = true;
  c.host = TELEOP_DEVICE_HOST;
  c.host_timeout_s = host_timeout_s;
  return c;
}

double counter(const LeaderDevice& device, const std::string& name) {
  runtime::NodeReport report;
  device.report_counters(report.counters);
  return test::counter(report, name);
}

// reads and writes at about the leader's period for `span`; the last state read, and how many reads failed
struct Ran {
  DeviceState state;
  int failed = 0;
};
Ran run_for(LeaderDevice& device, std::chrono::milliseconds span, double force_x_n = 0.0) {
  Ran ran;
  JointVector force{};
  force[0] = force_x_n;
  const auto until = std::chrono::steady_clock::now() + span;
  while (std::chrono::steady_clock::now() < until) {
    if (!device.read(ran.state)) ++ran.failed;
    (void)device.write(force);
    std::this_thread::sleep_for(1ms);
  }
  return ran;
}

TEST(IsolatedPlugin, TheHostedDeltaMovesWithTheHandAndGivesWayToTheForceRendered) {
  IsolatedPluginDevice device(delta({{"reach_z_m", "0.02"}, {"ramp_s", "0.2"}, {"frequency_hz", "0"}}));
  EXPECT_STREQ(device.name(), "simulated delta");
  EXPECT_GT(device.host_pid(), 0);
  const Ran reached = run_for(device, 600ms);
  EXPECT_EQ(reached.failed, 0);
  EXPECT_NEAR(reached.state.position_m[2], 0.02, 0.004) << "the hand took the handle up";
  EXPECT_EQ(reached.state.q_rad[0], 0.0) << "a Cartesian device leaves the joints as the leader set them";
  const Ran pushed = run_for(device, 500ms, 5.0);
  EXPECT_GT(pushed.state.position_m[0], 0.005) << "the handle gave way to 5 N along x";
  EXPECT_EQ(counter(device, "plugin_host_losses"), 0.0);
}

TEST(IsolatedPlugin, APluginThatCrashesTakesItsHostDownAndTheLeaderReadsItAsLost) {
  IsolatedPluginDevice device(delta({{"crash_after_reads", "300"}}, 0.3));
  DeviceState state;
  int reads = 0;
  const auto until = std::chrono::steady_clock::now() + 20s;
  while (device.read(state) && std::chrono::steady_clock::now() < until) {
    ++reads;
    (void)device.write(JointVector{});
    std::this_thread::sleep_for(1ms);
  }
  EXPECT_GT(reads, 0) << "it served before it crashed";
  EXPECT_FALSE(device.read(state)) << "the host died at its 300th read: lost";
  EXPECT_FALSE(device.write(JointVector{}));
  EXPECT_EQ(counter(device, "plugin_host_losses"), 1.0);
  int status = 0;
  EXPECT_EQ(::waitpid(device.host_pid(), &status, 0), device.host_pid());
  // SIGSEGV; a sanitizer's runtime in the host catches it, reports it and aborts or exits 1
  EXPECT_FALSE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "the plugin's crash ended the host";
}

TEST(IsolatedPlugin, AHostThatCannotOpenTheDeviceNamesThePluginsError) {
  try {
    IsolatedPluginDevice device(delta({{"stiffnes", "1"}}));
    FAIL() << "opened";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("unknown setting stiffnes"), std::string::npos) << e.what();
  }
}

// the leader's node on the hosted delta: it commands from the handle while the host lives; the
// host killed (as a crashing SDK would), the node holds with its hardware fault on the bus and
// cycles on
TEST(IsolatedPlugin, TheLeaderHoldsAndGoesOnWhenTheHostIsKilled) {
  test::NodeHarness harness{"leader"};
  const ConfigNode root = ConfigNode::load_string(
      "teleoperation: {architecture: pfc}\nleader:\n  joints: 7\n  feedback: {enabled: true}\n"
      "  home_rad: [0.0, -0.2438, 0.0, -2.2, 0.0, 1.96, 0.785]\n  arm_model: " +
          std::string(TELEOP_SOURCE_DIR) + "/config/models/panda.xml\n  device: plugin\n  plugin: {library: " +
          TELEOP_DELTA_PLUGIN + ", host_timeout_ms: 300, settings: {frequency_hz: 0}}\n",
      "leader.yaml");
  LeaderConfig config = parse_leader_config(root);
  LeaderNode node(config, harness.context);
  test::FollowingPeer<msg::CartesianCommand> follower(harness.peer, transport::topics::kLeaderCartesian, 7);
  ASSERT_TRUE(test::eventually([&] { return follower.state.matched() > 0 && follower.command.reader().matched() > 0; }));
  const auto cycle_for = [&](std::chrono::milliseconds span) {
    const auto until = std::chrono::steady_clock::now() + span;
    while (std::chrono::steady_clock::now() < until) {
      ASSERT_TRUE(follower.publish());
      node.cycle(harness.tick());
      std::this_thread::sleep_for(1ms);
    }
  };
  cycle_for(300ms);
  ASSERT_EQ(node.state(), msg::STATE_RUNNING);
  runtime::NodeReport before;
  node.fill_report(before);
  EXPECT_EQ(test::counter(before, "plugin_host_losses"), 0.0);
  const auto* device = dynamic_cast<const IsolatedPluginDevice*>(&node.device());
  ASSERT_NE(device, nullptr) << "isolated by default";
  ASSERT_EQ(::kill(device->host_pid(), SIGKILL), 0);
  cycle_for(800ms);
  EXPECT_EQ(node.state(), msg::STATE_SAFE_HOLD);
  std::vector<uint32_t> faults;
  node.active_faults(faults);
  EXPECT_EQ(faults, std::vector<uint32_t>{msg::FAULT_HARDWARE});
  runtime::NodeReport after;
  node.fill_report(after);
  EXPECT_EQ(test::counter(after, "plugin_host_losses"), 1.0);
  EXPECT_EQ(test::counter(after, "device_lost_events"), 1.0);
}

TEST(DeviceChannel, ASequenceLockRefusesAValueWrittenMeanwhile) {
  SeqLocked<JointVector> locked;
  JointVector v{};
  v[0] = 1.5;
  locked.store(v);
  JointVector out{};
  ASSERT_TRUE(locked.load(out));
  EXPECT_EQ(out[0], 1.5);
  locked.sequence.store(locked.sequence.load() + 1);  // a writer under way
  JointVector kept{};
  kept[0] = -1.0;
  EXPECT_FALSE(locked.load(kept));
  EXPECT_EQ(kept[0], -1.0) << "the reader keeps what it had";
}

}  // namespace
}  // namespace teleop::leader
