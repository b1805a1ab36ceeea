// The hand adapter against nine emulated drives on a VirtualCanBus, in simulated time: boot,
// configuration, enable walk, homing, tracking, every fault into safe hold and out by reset.
#include "teleop/hand/hand_adapter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "allocation_counter.h"
#include "hand_rig.h"
#include "teleop/can/cia402.h"

namespace teleop::hand::test {

using namespace can;  // the CANopen core the hand is built on
namespace {

using cia402::State;

HandTargets targets_at(double rad) {
  HandTargets t;
  t.position_rad.fill(rad);
  t.enable = true;
  return t;
}

// a fault reset command: the rising edge of fault_reset
void reset(HandRig& rig) {
  HandTargets t = targets_at(0.5);
  t.fault_reset = false;
  rig.adapter().set_command(t);
  rig.cycle();
  t.fault_reset = true;
  rig.adapter().set_command(t);
  rig.cycle();
}

TEST(HandAdapter, BootsConfiguresAndEnablesEveryDrive) {
  HandAdapterConfig config;
  config.gains.position_kp_a_per_rad = 25.0;
  HandRig rig(config);
  ASSERT_TRUE(rig.run_until(HandPhase::kOperational, 2.0)) << to_string(rig.adapter().phase()) << ": "
                                                           << rig.adapter().message();
  EXPECT_TRUE(rig.adapter().started());
  for (size_t i = 0; i < rig.drives(); ++i) {
    const drive::EmulatedDrive& d = rig.drive(i);
    EXPECT_EQ(d.nmt_state(), NmtState::kOperational);
    EXPECT_EQ(d.state(), State::kOperationEnabled) << "node " << int{d.node_id()};
    EXPECT_EQ(d.mode_of_operation(), cia402::kModeCyclicSynchronousPosition);
    EXPECT_FLOAT_EQ(d.config().control.position_kp_a_per_rad, 25.0f);  // the gains object, written as REAL32
    EXPECT_EQ(d.limit_min_ticks(), 0);
    EXPECT_EQ(d.limit_max_ticks(), *rig.adapter().channel(i).rad_to_ticks(1.0));
  }
  EXPECT_EQ(rig.adapter().stats().sdo_aborts, 0u);
  EXPECT_GT(rig.adapter().stats().tpdos_received, 0u);
}

TEST(HandAdapter, BootTimeoutNamesTheMissingNode) {
  HandRig rig({}, {5});
  ASSERT_TRUE(rig.run_until(HandPhase::kFailed, 3.0));
  EXPECT_NE(std::string(rig.adapter().message()).find("no boot-up or heartbeat from node 5 (Middle_Finger_Distal"),
            std::string::npos)
      << rig.adapter().message();
}

TEST(HandAdapter, SdoAbortWhileConfiguringNamesNodeObjectAndCode) {
  HandRig rig;
  rig.drive(2).set_sdo_refused(true);
  ASSERT_TRUE(rig.run_until(HandPhase::kFailed, 3.0));
  EXPECT_NE(std::string(rig.adapter().message()).find("configuring node 3: SDO write 0x1800:1 aborted with 0x08000021"),
            std::string::npos)
      << rig.adapter().message();
}

TEST(HandAdapter, TracksTargetsThroughThePackedRpdos) {
  HandRig rig;
  ASSERT_TRUE(rig.run_until(HandPhase::kOperational));
  HandTargets t;
  for (size_t m = 0; m < kHandMotors; ++m) t.position_rad[m] = 0.1 + 0.08 * static_cast<double>(m);
  t.enable = true;
  rig.adapter().set_command(t);
  rig.run(1.0);
  for (size_t m = 0; m < kHandMotors; ++m) {
    EXPECT_NEAR(rig.drive(m).position_rad(), t.position_rad[m], 2e-3) << "motor " << m;
    EXPECT_NEAR(rig.adapter().feedback().position_rad[m], t.position_rad[m], 2e-3) << "motor " << m;
  }
  // 20 joints from the 9 motors: the ring motor drives its distal joints too
  const HandJointVector q = rig.adapter().joint_positions();
  EXPECT_NEAR(q[0], t.position_rad[0], 2e-3);
  EXPECT_EQ(rig.adapter().phase(), HandPhase::kOperational);
}

TEST(HandAdapter, ClampsOutOfLimitCommandsAndRejectsNan) {
  HandRig rig;
  ASSERT_TRUE(rig.run_until(HandPhase::kOperational));
  HandTargets t = targets_at(0.5);
  t.position_rad[3] = 7.0;
  t.current_limit_a[4] = 99.0;
  rig.adapter().set_command(t);
  rig.cycle();
  EXPECT_EQ(rig.adapter().stats().clamped_commands, 1u);
  EXPECT_DOUBLE_EQ(rig.adapter().feedback().target_rad[3], 1.0);
  EXPECT_NE(rig.adapter().feedback().faults[3] & hand_fault::kLimit, 0u);
  rig.run(0.1);
  EXPECT_NEAR(rig.drive(4).current_limit_a(), 3.0, 1e-3);  // clamped to max_current_limit_a, sent by SDO

  HandTargets bad = targets_at(0.2);
  bad.position_rad[1] = std::numeric_limits<double>::quiet_NaN();
  rig.adapter().set_command(bad);
  rig.cycle();
  EXPECT_EQ(rig.adapter().stats().rejected_commands, 1u);
  EXPECT_DOUBLE_EQ(rig.adapter().feedback().target_rad[0], 0.5);  // the previous targets stay
  EXPECT_EQ(rig.adapter().phase(), HandPhase::kOperational);
}

TEST(HandAdapter, DisableQuickStopsAndEnableResumes) {
  HandRig rig;
  ASSERT_TRUE(rig.run_until(HandPhase::kOperational));
  HandTargets t = targets_at(0.3);
  t.enable = false;
  rig.adapter().set_command(t);
  rig.run(0.1);
  for (size_t i = 0; i < rig.drives(); ++i) EXPECT_EQ(rig.drive(i).state(), State::kQuickStopActive);
  t.enable = true;
  rig.adapter().set_command(t);
  rig.run(0.5);
  for (size_t i = 0; i < rig.drives(); ++i) {
    EXPECT_EQ(rig.drive(i).state(), State::kOperationEnabled);
    EXPECT_NEAR(rig.drive(i).position_rad(), 0.3, 2e-3);
  }
}

// One fault: it drives the safe state (quick stop, hold, fault reported with node and code),
// a reset while the cause persists keeps it there, a reset after the cause is gone recovers.
struct FaultCase {
  const char* name;
  uint32_t bit;
  void (*inject)(HandRig&);
  void (*clear)(HandRig&);
};

void expect_fault_and_recovery(const FaultCase& c) {
  HandRig rig;
  ASSERT_TRUE(rig.run_until(HandPhase::kOperational));
  rig.adapter().set_command(targets_at(0.4));
  rig.run(0.3);
  c.inject(rig);
  ASSERT_TRUE(rig.run_until(HandPhase::kSafeHold, 1.0)) << c.name;
  EXPECT_NE(rig.adapter().feedback().faults[3] & c.bit, 0u) << c.name << ": " << rig.adapter().message();
  EXPECT_NE(std::string(rig.adapter().message()).find("node"), std::string::npos);
  const double held = rig.adapter().feedback().position_rad[3];
  rig.adapter().set_command(targets_at(0.9));  // ignored while holding
  rig.run(0.3);
  EXPECT_NEAR(rig.adapter().feedback().target_rad[3], held, 0.02) << c.name;
  reset(rig);
  rig.run(0.1);
  EXPECT_EQ(rig.adapter().phase(), HandPhase::kSafeHold) << c.name << ": reset while the cause persists";
  c.clear(rig);
  rig.run(0.5);
  reset(rig);
  ASSERT_TRUE(rig.run_until(HandPhase::kOperational, 1.0)) << c.name << ": " << rig.adapter().message();
  EXPECT_EQ(rig.adapter().feedback().faults[3] & ~hand_fault::kLimit, 0u) << c.name;
  rig.adapter().set_command(targets_at(0.6));
  rig.run(0.6);
  EXPECT_NEAR(rig.drive(3).position_rad(), 0.6, 2e-3) << c.name;
}

TEST(HandAdapter, MissingHeartbeatHoldsAndRecovers) {
  expect_fault_and_recovery({"heartbeat", hand_fault::kHeartbeat,
                             [](HandRig& r) { r.drive(3).set_heartbeat_suppressed(true); },
                             [](HandRig& r) { r.drive(3).set_heartbeat_suppressed(false); }});
}

TEST(HandAdapter, StalePdoHoldsAndRecovers) {
  expect_fault_and_recovery({"pdo timeout", hand_fault::kStalePdo,
                             [](HandRig& r) { r.drive(3).drop_tpdos(drive::EmulatedDrive::kDropForever); },
                             [](HandRig& r) { r.drive(3).drop_tpdos(0); }});
}

TEST(HandAdapter, BusOffHoldsAndRecovers) {
  expect_fault_and_recovery({"bus-off", hand_fault::kBusOff,
                             [](HandRig& r) { r.adapter_endpoint().set_state(CanBusState::kBusOff); },
                             [](HandRig& r) { r.adapter_endpoint().set_state(CanBusState::kErrorActive); }});
}

TEST(HandAdapter, ErrorPassiveHoldsAndRecovers) {
  expect_fault_and_recovery({"error passive", hand_fault::kBusPassive,
                             [](HandRig& r) { r.adapter_endpoint().set_state(CanBusState::kErrorPassive); },
                             [](HandRig& r) { r.adapter_endpoint().set_state(CanBusState::kErrorActive); }});
}

TEST(HandAdapter, EmcyHoldsReportsTheCodeAndRecovers) {
  HandRig rig;
  ASSERT_TRUE(rig.run_until(HandPhase::kOperational));
  rig.adapter().set_command(targets_at(0.4));
  rig.run(0.3);
  rig.drive(6).raise_fault(emcy::kOverCurrent);
  ASSERT_TRUE(rig.run_until(HandPhase::kSafeHold, 1.0));
  const HandFeedback& fb = rig.adapter().feedback();
  EXPECT_NE(fb.faults[6] & hand_fault::kEmcy, 0u);
  EXPECT_EQ(fb.error_code[6], emcy::kOverCurrent);
  EXPECT_NE(std::string(rig.adapter().message()).find("node 7 (Ring_Finger): bits 0x"), std::string::npos)
      << rig.adapter().message();
  rig.run(0.1);
  EXPECT_NE(rig.adapter().feedback().faults[6] & hand_fault::kDrive, 0u);
  EXPECT_EQ(rig.drive(0).state(), State::kQuickStopActive);  // the others quick-stop and hold
  reset(rig);
  ASSERT_TRUE(rig.run_until(HandPhase::kOperational, 1.0)) << rig.adapter().message();
  EXPECT_EQ(rig.drive(6).state(), State::kOperationEnabled);
  EXPECT_EQ(rig.adapter().feedback().error_code[6], 0u);
  EXPECT_EQ(rig.adapter().stats().fault_resets, 1u);
}

TEST(HandAdapter, SdoAbortAtRunTimeHoldsWithTheAbortCode) {
  HandRig rig;
  ASSERT_TRUE(rig.run_until(HandPhase::kOperational));
  rig.drive(1).set_sdo_refused(true);
  HandTargets t = targets_at(0.4);
  t.current_limit_a.fill(1.0);  // a new current limit goes out by SDO
  rig.adapter().set_command(t);
  ASSERT_TRUE(rig.run_until(HandPhase::kSafeHold, 1.0));
  EXPECT_NE(rig.adapter().feedback().faults[1] & hand_fault::kSdo, 0u);
  EXPECT_EQ(rig.adapter().feedback().sdo_abort_code[1], sdo_abort::kLocalControl);
  rig.drive(1).set_sdo_refused(false);
  reset(rig);
  ASSERT_TRUE(rig.run_until(HandPhase::kOperational, 1.0)) << rig.adapter().message();
}

TEST(HandAdapter, ConfiguringSendsALostSdoWriteAgain) {
  // node 3's first SDO request is lost (as one reaching a node still initialising after the
  // reset, which ignores every frame): the adapter sends it again after the SDO timeout
  HandRig rig;
  bool dropped = false;
  for (int i = 0; i < 500 && rig.adapter().phase() != HandPhase::kOperational; ++i) {
    rig.cycle([&] {
      if (dropped || rig.adapter().phase() != HandPhase::kConfiguring) return;
      CanFrame f;
      while (rig.drive_endpoint(2).receive(f, std::chrono::nanoseconds::zero()) == CanStatus::kOk) {
        dropped = dropped || f.id == cob::kSdoRx + 3u;
      }
    });
  }
  EXPECT_TRUE(dropped);
  EXPECT_EQ(rig.adapter().phase(), HandPhase::kOperational) << rig.adapter().message();
}

TEST(HandAdapter, ConfiguringFailsWhenANodeNeverAnswersAnSdoWrite) {
  HandRig rig;
  for (int i = 0; i < 500 && rig.adapter().phase() != HandPhase::kFailed; ++i) {
    rig.cycle([&] {
      if (rig.adapter().phase() != HandPhase::kConfiguring) return;
      CanFrame f;
      while (rig.drive_endpoint(2).receive(f, std::chrono::nanoseconds::zero()) == CanStatus::kOk) {
      }
    });
  }
  ASSERT_EQ(rig.adapter().phase(), HandPhase::kFailed);
  EXPECT_NE(std::string(rig.adapter().message()).find("configuring node 3: no answer to SDO write"), std::string::npos)
      << rig.adapter().message();
  EXPECT_NE(std::string(rig.adapter().message()).find("(3 attempts)"), std::string::npos) << rig.adapter().message();
}

TEST(HandAdapter, RebootedNodeIsAFault) {
  HandRig rig;
  ASSERT_TRUE(rig.run_until(HandPhase::kOperational));
  ASSERT_EQ(rig.adapter_endpoint().send(*encode_nmt(NmtCommand::kResetNode, 8)), CanStatus::kOk);
  ASSERT_TRUE(rig.run_until(HandPhase::kSafeHold, 1.0));
  EXPECT_NE(rig.adapter().feedback().faults[7] & hand_fault::kHeartbeat, 0u);
}

TEST(HandAdapter, HomingFindsTheHardStopsAndSetsTheLimits) {
  HandAdapterConfig config;
  config.homing.enabled = true;
  HandRig rig(config);
  ASSERT_TRUE(rig.run_until(HandPhase::kHoming, 2.0)) << rig.adapter().message();
  ASSERT_TRUE(rig.run_until(HandPhase::kOperational, 3.0)) << rig.adapter().message();
  rig.run(0.5);  // back from the stop to the lower limit
  for (size_t m = 0; m < kHandMotors; ++m) {
    // the emulated stop is at -0.1 rad of the link, the config says -0.1: the frames agree
    EXPECT_NEAR(rig.adapter().feedback().position_rad[m], rig.drive(m).position_rad(), 0.01) << m;
    EXPECT_NEAR(rig.drive(m).position_rad(), 0.0, 0.01) << m;
    EXPECT_NE(rig.drive(m).limit_min_ticks(), std::numeric_limits<int32_t>::min()) << m;
  }
  rig.adapter().set_command(targets_at(0.5));
  rig.run(0.6);
  EXPECT_NEAR(rig.drive(8).position_rad(), 0.5, 0.01);
}

TEST(HandAdapter, HomingWithoutAStopFailsNamingTheNode) {
  HandAdapterConfig config;
  config.homing.enabled = true;
  config.homing.timeout_s = 0.5;
  config.homing.current_threshold_a = 5.0;  // above the drive's current limit: never reached
  HandRig rig(config);
  ASSERT_TRUE(rig.run_until(HandPhase::kFailed, 4.0));
  EXPECT_NE(std::string(rig.adapter().message()).find("homing: node 1 (Thumb_Flexion) found no hard stop"),
            std::string::npos)
      << rig.adapter().message();
}

TEST(HandAdapter, CycleAndCommandDoNotAllocate) {
  HandRig rig;
  ASSERT_TRUE(rig.run_until(HandPhase::kOperational));
  {
    teleop::test::ScopedAllocationCounter counter;
    for (int i = 0; i < 50; ++i) {
      HandTargets t = targets_at(0.2 + 0.001 * i);
      t.current_limit_a.fill(i < 25 ? 1.0 : 1.2);  // SDO writes queued and sent
      t.position_rad[0] = 9.0;                      // clamped
      rig.adapter().set_command(t);
      rig.adapter().cycle(rig.now_ns());
      (void)rig.adapter().joint_positions();
    }
    EXPECT_EQ(counter.count(), 0u);
  }
  // the fault paths too: into safe hold, the reset attempt
  rig.drive(2).raise_fault(emcy::kFollowingError);
  for (int i = 0; i < 5; ++i) rig.cycle();
  teleop::test::ScopedAllocationCounter counter;
  HandTargets t = targets_at(0.2);
  t.fault_reset = true;
  rig.adapter().set_command(t);
  for (int i = 0; i < 20; ++i) rig.adapter().cycle(rig.now_ns() + i * 4'000'000);
  EXPECT_EQ(counter.count(), 0u);
}

TEST(HandAdapter, WarnsAboveSeventyPercentBusLoad) {
  HandAdapterConfig config;
  EXPECT_FALSE(bus_load_warning(config).has_value());
  config.cycle_rate_hz = 1000.0;
  const auto warning = bus_load_warning(config);
  ASSERT_TRUE(warning.has_value());
  EXPECT_NE(warning->find("exceeds 70 %"), std::string::npos) << *warning;
  EXPECT_NE(warning->find("364 Hz"), std::string::npos) << *warning;
}

TEST(HandAdapter, RejectsInvalidConfiguration) {
  VirtualCanBus bus;
  auto ep = bus.open();
  HandAdapterConfig c;
  c.node_ids[4] = 3;
  EXPECT_THROW(HandAdapter(*ep, c), std::invalid_argument);
  c = {};
  c.min_position_rad[2] = 2.0;
  EXPECT_THROW(HandAdapter(*ep, c), std::invalid_argument);
  c = {};
  c.heartbeat_timeout_s = 0.05;
  EXPECT_THROW(HandAdapter(*ep, c), std::invalid_argument);
}

}  // namespace
}  // namespace teleop::hand::test
