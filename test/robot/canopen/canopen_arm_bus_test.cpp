// The master's CANopen side of an arm against emulated CiA 402 drives (teleop::drive) on a
// virtual bus: the start-up configures them by SDO, the cycle drives them in torque, and every
// fault class ends in a latched bus fault or the drives' own quick stop.
#include "canopen_arm_bus.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "teleop/can/virtual_can_bus.h"
#include "emulated_joint.h"
#include "teleop/drive/emulated_drive.h"

namespace teleop::robot {
namespace {

using can::cia402::State;
constexpr int64_t kMs = 1'000'000;

using test::emulated_joint;

class ArmRig {
 public:
  /// `drives` emulated drives, nodes 1.., and a master that believes `axis` of each and looks
  /// for them at node + `node_shift`.
  explicit ArmRig(size_t drives, CanopenBusConfig config = {}, const Cia402AxisConfig& axis = emulated_joint(),
                  int node_shift = 0)
      : master_ep_(bus_.open("master")) {
    for (size_t k = 0; k < drives; ++k) {
      drive::EmulatedDriveConfig d;
      d.node_id = static_cast<can::NodeId>(k + 1);
      d.initial_position_rad = 0.5;
      endpoints_.push_back(bus_.open("drive"));
      drives_.push_back(std::make_unique<drive::EmulatedDrive>(*endpoints_.back(), d));
      config.drives.push_back({static_cast<can::NodeId>(d.node_id + node_shift), axis});
    }
    arm_ = std::make_unique<CanopenArmBus>(*master_ep_, config);
    step_drives();  // powered on: boot-up, pre-operational
  }

  void step_drives() {
    for (auto& d : drives_) d->step(1e-3);
    now_ns_ += kMs;
  }
  void configure() {
    SdoWait wait;
    wait.pump = [this] { step_drives(); };
    wait.timeout = std::chrono::milliseconds(20);
    arm_->configure(wait, now_ns_);
  }
  /// The start-up's error message ("" when it succeeded).
  std::string configure_error() {
    try {
      configure();
    } catch (const std::runtime_error& e) {
      return e.what();
    }
    return "";
  }
  /// One 1 ms cycle of the master with these joint torques, then the drives' millisecond.
  void cycle(double torque_nm) {
    arm_->receive(now_ns_);
    for (size_t k = 0; k < arm_->size(); ++k) arm_->command(k, arm_->axis(k).command(torque_nm));
    arm_->send(now_ns_);
    step_drives();
  }
  bool all_enabled() const {
    for (size_t k = 0; k < arm_->size(); ++k) {
      if (!arm_->axis(k).enabled()) return false;
    }
    return true;
  }
  int enable() {
    for (int i = 1; i <= 20; ++i) {
      cycle(0.0);
      if (all_enabled()) return i;
    }
    return -1;
  }

  CanopenArmBus& arm() { return *arm_; }
  drive::EmulatedDrive& drive(size_t k) { return *drives_[k]; }
  int64_t now_ns() const { return now_ns_; }
  void idle_drives(int ms) {
    for (int i = 0; i < ms; ++i) step_drives();
  }

 private:
  can::VirtualCanBus bus_;
  std::unique_ptr<can::VirtualCanEndpoint> master_ep_;
  std::vector<std::unique_ptr<can::VirtualCanEndpoint>> endpoints_;
  std::vector<std::unique_ptr<drive::EmulatedDrive>> drives_;
  std::unique_ptr<CanopenArmBus> arm_;
  int64_t now_ns_ = 0;
};

TEST(CanopenArmBus, ConfiguresTheDrivesForTorqueAndDrivesThem) {
  ArmRig rig(2);
  rig.configure();
  EXPECT_GT(rig.enable(), 0);
  for (size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(rig.drive(k).nmt_state(), can::NmtState::kOperational);
    EXPECT_EQ(rig.drive(k).mode_of_operation(), can::cia402::kModeCyclicSynchronousTorque);
    EXPECT_EQ(rig.drive(k).abort_connection_option(), can::cia402::abort_connection::kQuickStop);
  }
  for (int i = 0; i < 100; ++i) rig.cycle(0.05);  // 50 mN m at the joints: they turn
  rig.arm().receive(rig.now_ns());                 // the feedback of the last SYNC
  for (size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(rig.drive(k).state(), State::kOperationEnabled);
    EXPECT_EQ(rig.drive(k).target_torque_permille(), 63);  // 0.05 N m / (10 mN m x 100 x 0.8) per mille
    // the axis reads the drive's true angle and rate (one SYNC old, through the encoder)
    EXPECT_NEAR(rig.arm().axis(k).position_rad(), rig.drive(k).position_rad(), 0.01);
    EXPECT_GT(rig.arm().axis(k).position_rad(), 0.5);
    EXPECT_NEAR(rig.arm().axis(k).velocity_radps(), rig.drive(k).velocity_radps(), 0.1);
    EXPECT_GT(rig.arm().axis(k).torque_nm(), 0.03);
  }
  EXPECT_TRUE(rig.arm().feedback_complete());
  EXPECT_EQ(rig.arm().stats().incomplete_cycles, 0u);
  EXPECT_EQ(rig.arm().fault().fault, BusFault::kNone);
}

// A master that skipped cycles sent its SYNCs further apart than its period: the rate is the
// positions' difference over the time between the SYNCs they answer, as sent (counted in periods
// it came out five times too fast after a 4 ms stall, and 1.8 times one sample later).
TEST(CanopenArmBus, TheRateSpansTheTimeBetweenTheSyncsAsSent) {
  ArmRig rig(1);
  rig.configure();
  ASSERT_GT(rig.enable(), 0);
  for (int i = 0; i < 100; ++i) rig.cycle(0.05);
  rig.idle_drives(4);  // the master stalls for 4 ms: its next SYNC goes out 5 ms after the last
  rig.cycle(0.05);
  rig.cycle(0.05);                  // takes the sample of the late SYNC
  rig.arm().receive(rig.now_ns());  // and the next one
  const double truth = rig.drive(0).velocity_radps();
  ASSERT_GT(truth, 0.05);
  EXPECT_NEAR(rig.arm().axis(0).velocity_radps(), truth, 0.2 * truth);
}

TEST(CanopenArmBus, StartUpErrorsNameTheDriveTheObjectAndTheAnswer) {
  Cia402AxisConfig believed = emulated_joint();
  believed.rated_torque_nm = 0.02;
  EXPECT_EQ(ArmRig(1, {}, believed).configure_error(),
            "drive 1: its rated torque 0x6076 is 10 mN m, the configuration says 20.000000 mN m: the torque would be "
            "scaled wrong");
  EXPECT_EQ(ArmRig(1, {}, emulated_joint(), 8).configure_error(),
            "SDO node 9, 0x1000:00: no answer within 20 ms (is the drive on the bus, with this node id?)");
  ArmRig refusing(1);
  refusing.drive(0).set_sdo_refused(true);
  EXPECT_EQ(refusing.configure_error(), "SDO node 1, 0x1000:00: the drive refused it (abort code 0x08000021)");
}

TEST(CanopenArmBus, RefusesAPlanThatOverloadsTheBus) {
  CanopenBusConfig config;
  for (can::NodeId n = 1; n <= 7; ++n) config.drives.push_back({n, emulated_joint()});
  can::VirtualCanBus bus;
  auto master = bus.open("master");
  try {
    CanopenArmBus arm(*master, config);
    FAIL() << "seven drives at 1 kHz on one classic bus";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()),
              "CANopen bus: 7 drives at 1000 Hz load the bus 171.7 % in the worst case, above 70 %: fewer drives "
              "per bus, or a longer SYNC period (docs/can_bus_budget.md)");
  }
  config.sync_period_s = 4e-3;  // 250 Hz: fits
  EXPECT_NO_THROW(CanopenArmBus(*master, config));
  // worst case: (SYNC 55 + 7 x (RPDO 4 B 95 + TPDO 8 B 135)) bits x 250 Hz + 8 heartbeats x 65 bits
  // x 100 Hz = 468,250 bit/s
  EXPECT_NEAR(canopen_bus_load(config).load_worst_case, 0.46825, 1e-9);
}

TEST(CanopenArmBus, ADriveFaultIsLatchedWithItsEmcyAndTheAxisFails) {
  ArmRig rig(2);
  rig.configure();
  ASSERT_GT(rig.enable(), 0);
  rig.drive(1).raise_fault(can::emcy::kOverCurrent);
  for (int i = 0; i < 5; ++i) rig.cycle(0.05);
  EXPECT_EQ(rig.arm().fault().fault, BusFault::kEmcy);
  EXPECT_EQ(rig.arm().fault().node, 2);
  EXPECT_EQ(rig.arm().fault().emcy_code, can::emcy::kOverCurrent);
  EXPECT_TRUE(rig.arm().axis(1).failed());
  EXPECT_FALSE(rig.arm().axis(0).failed());
}

TEST(CanopenArmBus, ASilentDriveIsLostAfterItsHeartbeatTime) {
  CanopenBusConfig config;
  config.drive_heartbeat_ms = 10;
  config.drive_lost_after_ms = 30;
  ArmRig rig(2, config);
  rig.configure();
  ASSERT_GT(rig.enable(), 0);
  for (int i = 0; i < 50; ++i) rig.cycle(0.0);
  rig.drive(0).set_heartbeat_suppressed(true);
  const int64_t silenced_ns = rig.now_ns();
  int64_t lost_ns = -1;
  for (int i = 0; i < 100 && lost_ns < 0; ++i) {
    rig.cycle(0.0);
    if (rig.arm().fault().fault != BusFault::kNone) lost_ns = rig.now_ns();
  }
  EXPECT_EQ(rig.arm().fault().fault, BusFault::kHeartbeatLost);
  EXPECT_EQ(rig.arm().fault().node, 1);
  // its last heartbeat was at most one period before the silence: lost 30..42 ms after it
  EXPECT_GT(lost_ns - silenced_ns, 20 * kMs);
  EXPECT_LE(lost_ns - silenced_ns, 42 * kMs);
}

TEST(CanopenArmBus, DrivesThatLoseTheMasterQuickStopByThemselves) {
  CanopenBusConfig config;
  config.master_heartbeat_ms = 10;
  config.master_lost_after_ms = 50;
  ArmRig rig(2, config);
  rig.configure();
  ASSERT_GT(rig.enable(), 0);
  for (int i = 0; i < 100; ++i) rig.cycle(0.05);
  // the master dies: nothing more from it, the drives run on
  int stopped_after_ms = -1;
  for (int ms = 1; ms <= 100 && stopped_after_ms < 0; ++ms) {
    rig.idle_drives(1);
    if (rig.drive(0).state() == State::kQuickStopActive && rig.drive(1).state() == State::kQuickStopActive) {
      stopped_after_ms = ms;
    }
  }
  // its last heartbeat went out at most 10 ms before it died
  EXPECT_GT(stopped_after_ms, 40);
  EXPECT_LE(stopped_after_ms, 52);
  EXPECT_EQ(rig.drive(0).stats().heartbeat_timeouts, 1u);
}

}  // namespace
}  // namespace teleop::robot
