// The hand node with a real DDS participant on one side and nine emulated drives on a
// VirtualCanBus on the other, the drives stepped in real time by a thread of their own.
#include "teleop/hand/hand_node.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <thread>

#include "allocation_counter.h"
#include "node_harness.h"
#include "teleop/can/cia301.h"
#include "teleop/can/virtual_can_bus.h"
#include "teleop/drive/emulated_drive.h"
#include "teleop/drive/drive_objects.h"

namespace teleop::hand {
namespace {

// nine drives on the bus, stepped every millisecond until destroyed
class DriveThread {
 public:
  explicit DriveThread(can::VirtualCanBus& bus) {
    for (can::NodeId node = 1; node <= 9; ++node) {
      endpoints_.push_back(bus.open("drive"));
      drive::EmulatedDriveConfig c;
      c.node_id = node;
      drives_.push_back(std::make_unique<drive::EmulatedDrive>(*endpoints_.back(), c));
    }
    thread_ = std::thread([this] {
      while (!stop_) {
        for (auto& d : drives_) d->step(1e-3);
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
      }
    });
  }
  ~DriveThread() {
    stop_ = true;
    thread_.join();
  }

 private:
  std::vector<std::unique_ptr<can::VirtualCanEndpoint>> endpoints_;
  std::vector<std::unique_ptr<drive::EmulatedDrive>> drives_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

HandNodeConfig config() {
  HandNodeConfig c;
  c.interface = "virtual";
  c.command_timeout_s = 0.5;
  return c;
}

class HandNodeTest : public ::testing::Test {
 protected:
  can::VirtualCanBus bus;
  std::unique_ptr<can::VirtualCanEndpoint> tool = bus.open("tool");  // a second master, like cansend
  DriveThread drives{bus};
  test::NodeHarness harness{"hand"};
  double rate_hz = harness.node_config.rate_hz = 250;  // the SYNC rate, before the node exists
  HandNode node{config(), harness.context, bus.open("hand")};
  transport::Publication<msg::HandCommand> command{harness.peer, transport::topics::kHandCommand, "operator"};
  transport::Subscription<msg::HandState> state{harness.peer, transport::topics::kHandState};
  transport::Subscription<msg::JointState> joints{harness.peer, transport::topics::kHandJoints};

  void SetUp() override {
    ASSERT_TRUE(test::eventually([&] { return command.matched() > 0 && state.reader().matched() > 0; }));
  }

  // commands and cycles for `seconds`, one cycle every 4 ms
  void run(double target_rad, double seconds, bool fault_reset = false) {
    for (int i = 0; i < static_cast<int>(seconds / 4e-3); ++i) {
      auto& c = command.sample();
      c.target_position_rad().fill(target_rad);
      c.enable(true);
      c.fault_reset(fault_reset);
      ASSERT_TRUE(command.publish());
      std::this_thread::sleep_for(std::chrono::milliseconds(4));
      node.cycle(harness.tick());
      state.poll();
      joints.poll();
    }
  }
};

TEST_F(HandNodeTest, FollowsHandCommandAndPublishesStateAndTwentyJoints) {
  EXPECT_EQ(node.state(), msg::STATE_RUNNING);
  run(0.4, 1.2);
  ASSERT_TRUE(state.has_sample());
  for (size_t m = 0; m < 9; ++m) EXPECT_NEAR(state.latest().position_rad()[m], 0.4, 0.01) << m;
  ASSERT_TRUE(joints.has_sample());
  ASSERT_EQ(joints.latest().q_rad().size(), 20u);
  EXPECT_NEAR(joints.latest().q_rad()[0], 0.4, 0.01);
  std::vector<uint32_t> faults;
  node.active_faults(faults);
  EXPECT_TRUE(faults.empty()) << faults.front();
}

TEST_F(HandNodeTest, EmcyIsReportedAsSafeHoldAndFaultResetRecovers) {
  run(0.3, 0.4);
  // a tool raises an over-current fault in node 4 through the fault injection object
  ASSERT_EQ(tool->send(*can::encode_sdo_download_request(4, drive::drive_od::kFaultInjection, drive::drive_od::inject::kRaiseFault,
                                                         can::emcy::kOverCurrent, 4)),
            can::CanStatus::kOk);
  run(0.3, 0.2);
  EXPECT_EQ(node.state(), msg::STATE_SAFE_HOLD);
  std::vector<uint32_t> faults;
  node.active_faults(faults);
  EXPECT_NE(std::find(faults.begin(), faults.end(), msg::FAULT_HARDWARE), faults.end());
  EXPECT_NE(state.latest().faults()[3] & msg::HAND_FAULT_EMCY, 0u);
  EXPECT_EQ(state.latest().error_code()[3], can::emcy::kOverCurrent);
  run(0.5, 0.5, true);
  EXPECT_EQ(node.state(), msg::STATE_RUNNING) << node.adapter().message();
  run(0.5, 0.8, true);
  EXPECT_NEAR(state.latest().position_rad()[3], 0.5, 0.01);
  EXPECT_EQ(state.latest().faults()[3], 0u);
}

TEST_F(HandNodeTest, OutOfLimitCommandIsClampedAndReported) {
  run(1.7, 0.8);
  EXPECT_NEAR(state.latest().position_rad()[0], 1.0, 0.01);
  EXPECT_NE(state.latest().faults()[0] & msg::HAND_FAULT_LIMIT, 0u);
  std::vector<uint32_t> faults;
  node.active_faults(faults);
  EXPECT_NE(std::find(faults.begin(), faults.end(), msg::FAULT_COMMAND_REJECTED), faults.end());
}

TEST_F(HandNodeTest, CycleDoesNotAllocate) {
  run(0.2, 0.2);
  auto& c = command.sample();
  c.target_position_rad().fill(0.25);
  ASSERT_TRUE(command.publish());
  std::this_thread::sleep_for(std::chrono::milliseconds(4));
  test::ScopedAllocationCounter counter;
  for (int i = 0; i < 20; ++i) node.cycle(harness.tick());
  EXPECT_EQ(counter.count(), 0u);
}

TEST(HandNode, StartUpFailureNamesTheMissingNode) {
  can::VirtualCanBus bus;
  test::NodeHarness harness{"hand"};
  harness.node_config.rate_hz = 250;
  HandNodeConfig c = config();
  c.adapter.boot_timeout_s = 0.2;
  try {
    HandNode node(c, harness.context, bus.open("hand"));
    FAIL() << "started without drives";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("no boot-up or heartbeat from node 1"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace teleop::hand
