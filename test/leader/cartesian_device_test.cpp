// A Cartesian device (a 6-DoF mouse, a gamepad: DeviceSpec::cartesian()) driving the leader under
// pfc: its handle's motion becomes the follower's Cartesian command from the follower's home, the
// dead-man and the clutch hold the command without a jump when it resumes, the workspace box
// bounds it, and a device that cannot be read (unplugged) holds the leader until it is back.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <thread>

#include "leader_config.h"
#include "leader_node.h"
#include "following_peer.h"
#include "node_harness.h"
#include "report_counter.h"
#include "teleop/leader/simulated_devices.h"

namespace teleop::leader {
namespace {

// what the test moves: the handle's position about its start, its buttons, whether it is there
struct Handle {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  uint32_t buttons = 0;
  bool connected = true;
};

class HandleDevice final : public LeaderDevice {
 public:
  explicit HandleDevice(std::shared_ptr<Handle> handle) : handle_(std::move(handle)) {}
  size_t joints() const override { return 0; }
  bool read(DeviceState& state) override {
    for (int i = 0; i < 3; ++i) state.position_m[static_cast<size_t>(i)] = handle_->position[i];
    state.buttons |= handle_->buttons;
    return handle_->connected;
  }
  bool write(const JointVector&) override { return true; }
  const char* name() const override { return "handle"; }

 private:
  std::shared_ptr<Handle> handle_;
};

class HandleSpec final : public DeviceSpec {
 public:
  explicit HandleSpec(std::shared_ptr<Handle> handle) : handle_(std::move(handle)) {}
  const char* device() const override { return "handle"; }
  bool cartesian() const override { return true; }
  std::unique_ptr<LeaderDevice> make(const DeviceSetup&) const override { return std::make_unique<HandleDevice>(handle_); }

 private:
  std::shared_ptr<Handle> handle_;
};

LeaderConfig config(const std::shared_ptr<Handle>& handle) {
  DeviceRegistry devices;
  add_simulated_devices(devices);
  devices.add("handle", [handle](const ConfigNode&) { return std::make_shared<HandleSpec>(handle); });
  const ConfigNode root = ConfigNode::load_string(
      "teleoperation: {architecture: pfc}\nleader:\n  joints: 7\n  feedback: {enabled: false}\n  device: handle\n  peer_timeout_ms: 50\n  arm_model: " +
          std::string(TELEOP_SOURCE_DIR) +
          "/config/models/panda.xml\n  home_rad: [0.0, -0.2438, 0.0, -2.2, 0.0, 1.96, 0.785]\n"
          "  buttons: {dead_man: 0, clutch: 1}\n"
          "  workspace_box_m: {min: [0.2, -0.5, 0.2], max: [0.8, 0.5, 0.8]}\n",
      "leader.yaml");
  return parse_leader_config(root, devices);
}

// the follower's side of the Cartesian commands, and the target it was sent last
struct CartesianFollower : test::FollowingPeer<msg::CartesianCommand> {
  explicit CartesianFollower(transport::Participant& p)
      : FollowingPeer(p, transport::topics::kLeaderCartesian, 7) {}
  Eigen::Vector3d target() const {
    const auto& p = command.latest().target_pose().position_m();
    return {p.x(), p.y(), p.z()};
  }
};

class CartesianDeviceTest : public ::testing::Test {
 protected:
  std::shared_ptr<Handle> handle = std::make_shared<Handle>();
  test::NodeHarness harness{"leader"};
  LeaderNode node{config(handle), harness.context};
  CartesianFollower follower{harness.peer};
  Eigen::Vector3d home;

  void SetUp() override {
    handle->buttons = 1u << 0;  // the dead-man held
    ASSERT_TRUE(test::eventually([&] { return follower.state.matched() > 0 && follower.command.reader().matched() > 0; }));
    ASSERT_TRUE(test::eventually([&] {
      step();
      return node.state() == msg::STATE_RUNNING && follower.command.has_sample();
    }));
    home = follower.target();
  }
  void step(int cycles = 1) {
    for (int i = 0; i < cycles; ++i) {
      ASSERT_TRUE(follower.publish());
      std::this_thread::sleep_for(std::chrono::microseconds(500));
      node.cycle(harness.tick());
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    follower.command.poll();
  }
};

TEST_F(CartesianDeviceTest, TheHandlesMotionMovesTheCommandFromTheFollowersHome) {
  EXPECT_GT(home.norm(), 0.3) << "the panda's flange at home, not the handle's origin";
  handle->position = {0.02, -0.01, 0.03};
  step(5);
  EXPECT_TRUE(follower.target().isApprox(home + Eigen::Vector3d(0.02, -0.01, 0.03), 1e-9)) << follower.target();
}

TEST_F(CartesianDeviceTest, TheDeadManReleasedOrTheClutchHeldHoldsTheCommandAndItResumesWithoutAJump) {
  handle->buttons = 0;  // the dead-man let go
  handle->position = {0.05, 0.0, 0.0};
  step(5);
  EXPECT_TRUE(follower.target().isApprox(home, 1e-12)) << follower.target();
  handle->buttons = 1u << 0;  // held again: motion from here on counts
  step(3);
  handle->position = {0.06, 0.0, 0.0};
  step(3);
  EXPECT_TRUE(follower.target().isApprox(home + Eigen::Vector3d(0.01, 0.0, 0.0), 1e-9)) << follower.target() - home;
  handle->buttons = 1u << 0 | 1u << 1;  // the clutch: the device moves freely
  handle->position = {0.0, 0.0, 0.0};
  step(3);
  EXPECT_TRUE(follower.target().isApprox(home + Eigen::Vector3d(0.01, 0.0, 0.0), 1e-9));
}

TEST_F(CartesianDeviceTest, TheWorkspaceBoxStopsTheCommandAndMotionBackActsAtOnce) {
  const double to_wall = 0.8 - home.z();
  handle->position = {0.0, 0.0, to_wall + 0.2};  // 0.2 m past the box's top
  step(3);
  EXPECT_NEAR(follower.target().z(), 0.8, 1e-12);
  handle->position = {0.0, 0.0, to_wall + 0.15};  // 5 cm back: the command leaves the wall at once
  step(3);
  EXPECT_NEAR(follower.target().z(), 0.75, 1e-9);
}

TEST_F(CartesianDeviceTest, AnUnpluggedDeviceHoldsTheLeaderUntilItIsBack) {
  handle->connected = false;
  handle->position = {0.04, 0.0, 0.0};
  step(3);
  EXPECT_EQ(node.state(), msg::STATE_SAFE_HOLD);
  EXPECT_TRUE(follower.target().isApprox(home, 1e-12));
  std::vector<uint32_t> faults;
  node.active_faults(faults);
  EXPECT_EQ(faults, std::vector<uint32_t>{msg::FAULT_HARDWARE});
  handle->connected = true;
  step(3);
  EXPECT_EQ(node.state(), msg::STATE_RUNNING);
  EXPECT_TRUE(follower.target().isApprox(home, 1e-9)) << "back where it was told to stop, no jump";
  runtime::NodeReport report;
  node.fill_report(report);
  EXPECT_EQ(test::counter(report, "device_lost_events"), 1.0);
}

}  // namespace
}  // namespace teleop::leader
