// The follower's `hardware: canopen` against emulated CiA 402 drives on two virtual buses: the
// start leaves them holding, the follower's torque resumes them, its hold quick-stops them, and a
// failed drive makes every drive hold; the `canopen:` keys and their errors.
#include "canopen_hardware.h"

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "teleop/can/virtual_can_bus.h"
#include "emulated_joint.h"
#include "teleop/drive/emulated_drive.h"

namespace teleop::robot {
namespace {

using can::cia402::State;

using test::emulated_joint;

// three joints: nodes 1 and 2 on "canA", node 5 on "canB"
class HardwareRig {
 public:
  HardwareRig() {
    const std::vector<std::pair<std::string, uint8_t>> placement{{"canA", 1}, {"canA", 2}, {"canB", 5}};
    buses_.push_back(std::make_unique<can::VirtualCanBus>());
    buses_.push_back(std::make_unique<can::VirtualCanBus>());
    for (const auto& [bus, node] : placement) {
      can::VirtualCanBus& b = *buses_[bus == "canA" ? 0 : 1];
      drive::EmulatedDriveConfig d;
      d.node_id = node;
      d.initial_position_rad = 0.5;
      endpoints_.push_back(b.open("drive"));
      drives_.push_back(std::make_unique<drive::EmulatedDrive>(*endpoints_.back(), d));
      config_.joints.push_back({bus, node, emulated_joint(), -0.1, 1.2});
    }
    masters_.push_back(buses_[0]->open("master"));
    masters_.push_back(buses_[1]->open("master"));
    step();  // powered on
  }
  void step() {
    for (auto& d : drives_) d->step(1e-3);
    now_ns_ += 1'000'000;
  }
  std::unique_ptr<CanopenHardware> start() {
    SdoWait wait;
    wait.pump = [this] { step(); };
    wait.timeout = std::chrono::milliseconds(20);
    return std::make_unique<CanopenHardware>(config_, 1e-3, std::vector<can::CanBus*>{masters_[0].get(), masters_[1].get()},
                                             wait, [this] { return now_ns_; });
  }
  drive::EmulatedDrive& drive(size_t k) { return *drives_[k]; }
  bool all_in(State s) const {
    for (const auto& d : drives_) {
      if (d->state() != s) return false;
    }
    return true;
  }
  CanopenHardwareConfig& config() { return config_; }
  /// A listener on bus canA (0) or canB (1): every frame sent there from now on.
  std::unique_ptr<can::VirtualCanEndpoint> listen(size_t bus) { return buses_[bus]->open("listener"); }

 private:
  std::vector<std::unique_ptr<can::VirtualCanBus>> buses_;
  std::vector<std::unique_ptr<can::VirtualCanEndpoint>> endpoints_;
  std::vector<std::unique_ptr<can::VirtualCanEndpoint>> masters_;
  std::vector<std::unique_ptr<drive::EmulatedDrive>> drives_;
  CanopenHardwareConfig config_;
  int64_t now_ns_ = 0;
};

// one follower cycle: read, then the torque (or the hold), then the drives' millisecond
HardwareStatus cycle(HardwareRig& rig, CanopenHardware& hw, ArmState& state, double torque_nm, bool hold = false) {
  const HardwareStatus status = hw.read(state);
  JointVector tau{};
  for (size_t k = 0; k < hw.joints(); ++k) tau[k] = torque_nm;
  EXPECT_EQ(hold ? hw.hold() : hw.write(tau), HardwareStatus::kOk);
  rig.step();
  return status;
}

TEST(CanopenHardware, StartsHoldingThenTheFollowersTorqueDrivesEveryJoint) {
  HardwareRig rig;
  auto hw = rig.start();
  EXPECT_STREQ(hw->name(), "canopen:canA,canB");
  EXPECT_EQ(hw->joints(), 3u);
  EXPECT_TRUE(rig.all_in(State::kQuickStopActive));  // holding by the drives' own position loops
  ArmState state;
  ASSERT_EQ(hw->read(state), HardwareStatus::kOk);
  for (size_t k = 0; k < 3; ++k) EXPECT_NEAR(state.q_rad[k], 0.5, 0.01);
  for (int i = 0; i < 100; ++i) EXPECT_NE(cycle(rig, *hw, state, 0.05), HardwareStatus::kFault);
  EXPECT_TRUE(rig.all_in(State::kOperationEnabled));
  for (size_t k = 0; k < 3; ++k) {
    EXPECT_GT(state.q_rad[k], 0.55) << k;  // pushed by 50 mN m
    EXPECT_NEAR(state.q_rad[k], rig.drive(k).position_rad(), 0.01);
    EXPECT_NEAR(state.tau_measured_nm[k], 0.05, 0.005);
  }
  EXPECT_GT(state.measured_ns, 0);
  const HardwareLimits limits = hw->limits();
  EXPECT_EQ(limits.q_max_rad[2], 1.2);
  EXPECT_EQ(limits.max_torque_nm[0], 1.0);
}

TEST(CanopenHardware, HoldQuickStopsTheDrivesAndTheNextTorqueResumesThem) {
  HardwareRig rig;
  auto hw = rig.start();
  ArmState state;
  for (int i = 0; i < 50; ++i) cycle(rig, *hw, state, 0.05);
  for (int i = 0; i < 50; ++i) EXPECT_NE(cycle(rig, *hw, state, 0.05, true), HardwareStatus::kFault);
  EXPECT_TRUE(rig.all_in(State::kQuickStopActive));
  const double held = rig.drive(0).position_rad();
  for (int i = 0; i < 20; ++i) cycle(rig, *hw, state, 0.05, true);
  EXPECT_NEAR(rig.drive(0).position_rad(), held, 1e-3);
  for (int i = 0; i < 20; ++i) EXPECT_EQ(cycle(rig, *hw, state, 0.05), HardwareStatus::kOk);
  EXPECT_TRUE(rig.all_in(State::kOperationEnabled));
}

TEST(CanopenHardware, OneFailedDriveMakesEveryDriveHold) {
  HardwareRig rig;
  auto hw = rig.start();
  ArmState state;
  for (int i = 0; i < 50; ++i) cycle(rig, *hw, state, 0.05);
  rig.drive(2).raise_fault(can::emcy::kOverCurrent);
  HardwareStatus status = HardwareStatus::kOk;
  for (int i = 0; i < 10; ++i) status = cycle(rig, *hw, state, 0.05);
  EXPECT_EQ(status, HardwareStatus::kFault);
  EXPECT_EQ(rig.drive(0).state(), State::kQuickStopActive);
  EXPECT_EQ(rig.drive(1).state(), State::kQuickStopActive);
  EXPECT_EQ(rig.drive(2).state(), State::kFault);
  std::vector<std::pair<std::string, double>> counters;
  hw->report_counters(counters);
  EXPECT_EQ(counters[4], (std::pair<std::string, double>{"canopen_fault", static_cast<double>(BusFault::kEmcy)}));
  EXPECT_EQ(counters[5], (std::pair<std::string, double>{"canopen_fault_node", 5}));
  EXPECT_EQ(counters[6], (std::pair<std::string, double>{"canopen_fault_emcy_code", can::emcy::kOverCurrent}));
}

// What CiA 402 asks of a master that sees a drive's EMCY: the other drives on quick stop within
// two SYNC periods. Read off bus canA's frames: node 2's EMCY, then the SYNCs until node 1's
// RPDO carries the quick stop (0x0002)
TEST(CanopenHardware, AnEmcyQuickStopsTheOtherDrivesWithinTwoSyncs) {
  HardwareRig rig;
  auto hw = rig.start();
  ArmState state;
  for (int i = 0; i < 20; ++i) cycle(rig, *hw, state, 0.05);
  auto listener = rig.listen(0);
  rig.drive(1).raise_fault(can::emcy::kOverCurrent);
  for (int i = 0; i < 10; ++i) cycle(rig, *hw, state, 0.05);
  bool emcy_seen = false;
  int syncs_after = 0;
  int quick_stop_after = -1;
  can::CanFrame f;
  while (listener->receive(f, std::chrono::nanoseconds::zero()) == can::CanStatus::kOk && quick_stop_after < 0) {
    if (f.id == can::cob::kEmcy + 2u) emcy_seen = true;
    if (!emcy_seen) continue;
    if (f.id == can::cob::kSync) ++syncs_after;
    if (f.id == can::rpdo_cob_id(1, 1) && f.data[0] == 0x02 && f.data[1] == 0x00) quick_stop_after = syncs_after;
  }
  ASSERT_TRUE(emcy_seen);
  // the quick stop goes out before the next SYNC after the EMCY is read: 0 or 1 SYNC after it,
  // and takes effect at the SYNC that follows
  EXPECT_GE(quick_stop_after, 0);
  EXPECT_LE(quick_stop_after, 1);
  EXPECT_EQ(rig.drive(0).state(), State::kQuickStopActive);
}

TEST(CanopenHardware, MissingFeedbackIsStaleNotAFault) {
  HardwareRig rig;
  auto hw = rig.start();
  ArmState state;
  for (int i = 0; i < 20; ++i) cycle(rig, *hw, state, 0.0);
  rig.drive(1).drop_tpdos(10);
  int stale = 0;
  for (int i = 0; i < 30; ++i) {
    const HardwareStatus s = cycle(rig, *hw, state, 0.0, stale > 0 && i < 20);
    EXPECT_NE(s, HardwareStatus::kFault);
    stale += s == HardwareStatus::kStale ? 1 : 0;
  }
  // 10 SYNCs unanswered, stale once the feedback is older than 5 ms: about 5 cycles
  EXPECT_GE(stale, 4);
  EXPECT_LE(stale, 7);
  EXPECT_EQ(hw->read(state), HardwareStatus::kOk);
}

TEST(CanopenHardware, ADriveThatCannotBeEnabledFailsTheStartNamingIt) {
  HardwareRig rig;
  rig.config().enable_timeout_s = 0.05;
  rig.drive(2).drop_tpdos(drive::EmulatedDrive::kDropForever);
  try {
    rig.start();
    FAIL() << "started without node 5's feedback";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("joint 3 (node 5)"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace teleop::robot
