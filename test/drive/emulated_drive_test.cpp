// The emulated CiA 402 drive on a VirtualCanBus, driven by a test master: boot-up and
// heartbeat, NMT, SDO server, 402 walk, CSP tracking, current limit, hard stops, determinism.
// PDO configuration and fault injection: emulated_drive_pdo_fault_test.cpp.
#include "teleop/drive/emulated_drive.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "allocation_counter.h"
#include "drive_rig.h"
#include "teleop/drive/drive_objects.h"

namespace teleop::drive::test {

using namespace can;  // the CANopen core the drive is built on

namespace {

// --- NMT, boot-up, heartbeat ----------------------------------------------------------------------

TEST(EmulatedDrive, SendsBootUpOnFirstStepThenHeartbeatsEveryPeriod) {
  DriveRig rig;
  EXPECT_FALSE(rig.drive().booted());
  rig.run(1e-3);
  ASSERT_FALSE(rig.received().empty());
  EXPECT_EQ(rig.received()[0].id, 0x701u);
  EXPECT_EQ(rig.received()[0].dlc, 1);
  EXPECT_EQ(rig.received()[0].data[0], 0x00);  // boot-up
  EXPECT_EQ(rig.drive().nmt_state(), NmtState::kPreOperational);
  EXPECT_EQ(rig.drive().state(), State::kSwitchOnDisabled);
  rig.clear_received();
  rig.run(1.0);
  const auto hb = heartbeats(rig);
  EXPECT_EQ(hb.size(), 10u);  // 100 ms producer time
  for (const auto& h : hb) EXPECT_EQ(h.state, NmtState::kPreOperational);
}

TEST(EmulatedDrive, HeartbeatFollowsNmtState) {
  DriveRig rig;
  rig.run(1e-3);
  const struct {
    NmtCommand command;
    NmtState state;
  } steps[] = {{NmtCommand::kStart, NmtState::kOperational},
               {NmtCommand::kStop, NmtState::kStopped},
               {NmtCommand::kEnterPreOperational, NmtState::kPreOperational}};
  for (const auto& s : steps) {
    rig.send(encode_nmt(s.command, rig.node()));
    rig.clear_received();
    rig.run(0.1);
    const auto hb = heartbeats(rig);
    ASSERT_EQ(hb.size(), 1u);
    EXPECT_EQ(hb[0].state, s.state);
    EXPECT_EQ(rig.drive().nmt_state(), s.state);
  }
}

TEST(EmulatedDrive, IgnoresNmtForOtherNodesAndObeysBroadcast) {
  DriveRig rig;
  rig.run(1e-3);
  rig.send(encode_nmt(NmtCommand::kStart, 2));
  rig.run(1e-3);
  EXPECT_EQ(rig.drive().nmt_state(), NmtState::kPreOperational);
  rig.send(encode_nmt(NmtCommand::kStart, 0));
  rig.run(1e-3);
  EXPECT_EQ(rig.drive().nmt_state(), NmtState::kOperational);
}

TEST(EmulatedDrive, ResetNodeRebootsWithDefaultsAndResetCommunicationKeepsApplication) {
  DriveRig rig;
  rig.run(1e-3);
  rig.write(od::kModesOfOperation, 0, 8, 1);
  rig.write(0x1017, 0, 50, 2);

  rig.clear_received();
  rig.send(encode_nmt(NmtCommand::kResetCommunication, rig.node()));
  rig.run(1e-3);
  ASSERT_FALSE(rig.received().empty());
  EXPECT_EQ(rig.received()[0], *encode_heartbeat(rig.node(), NmtState::kBootUp));
  EXPECT_EQ(rig.sdo_read(0x1017, 0)->data, 100u);               // communication object: default again
  EXPECT_EQ(rig.sdo_read(od::kModesOfOperation, 0)->data, 8u);  // application object: kept

  rig.clear_received();
  rig.send(encode_nmt(NmtCommand::kResetNode, rig.node()));
  rig.run(1e-3);
  ASSERT_FALSE(rig.received().empty());
  EXPECT_EQ(rig.received()[0], *encode_heartbeat(rig.node(), NmtState::kBootUp));
  EXPECT_EQ(rig.drive().nmt_state(), NmtState::kPreOperational);
  EXPECT_EQ(rig.sdo_read(od::kModesOfOperation, 0)->data, 0u);
}

// --- SDO server -----------------------------------------------------------------------------------

TEST(EmulatedDrive, SdoServerAnswersReads) {
  DriveRig rig;
  rig.run(1e-3);
  const auto type = rig.sdo_read(0x1000, 0);
  ASSERT_TRUE(type.ok());
  EXPECT_EQ(type->type, SdoType::kUploadResponse);
  EXPECT_EQ(type->size, 4);
  EXPECT_EQ(type->data, EmulatedDrive::kDeviceType);
  EXPECT_EQ(rig.sdo_read(0x1018, 1)->data, EmulatedDriveConfig{}.vendor_id);
  const auto sw = rig.sdo_read(od::kStatusword, 0);
  EXPECT_EQ(sw->size, 2);
  EXPECT_EQ(sw->data, 0x0250u);  // switch on disabled, voltage enabled, remote
  EXPECT_EQ(rig.sdo_read(od::kModesOfOperationDisplay, 0)->data, 0u);
  EXPECT_EQ(rig.sdo_read(od::kMotorRatedCurrent, 0)->data, 1000u);  // mA
  EXPECT_EQ(rig.sdo_read(0x1A00, 1)->data, 0x60640020u);            // TPDO1 maps position actual first
}

TEST(EmulatedDrive, SdoServerWritesAndReadsBack) {
  DriveRig rig;
  rig.run(1e-3);
  rig.write(0x1017, 0, 250, 2);
  EXPECT_EQ(rig.sdo_read(0x1017, 0)->data, 250u);
  rig.write(od::kTargetPosition, 0, static_cast<uint32_t>(-12345), 4);
  EXPECT_EQ(static_cast<int32_t>(rig.sdo_read(od::kTargetPosition, 0)->data), -12345);
  EXPECT_EQ(rig.drive().target_ticks(), -12345);
  rig.write(od::kSoftwarePositionLimit, 2, 5000, 4);
  EXPECT_EQ(rig.sdo_read(od::kSoftwarePositionLimit, 2)->data, 5000u);
  // a download without size indication is accepted for the object's own size
  const auto r = rig.sdo(Result<CanFrame>([&] {
    CanFrame f = *encode_sdo_download_request(rig.node(), 0x1017, 0, 0, 2);
    f.data[0] = 0x22;  // expedited, size not indicated
    f.data[4] = 0x2C;
    f.data[5] = 0x01;
    return f;
  }()));
  EXPECT_EQ(r->type, SdoType::kDownloadResponse);
  EXPECT_EQ(rig.sdo_read(0x1017, 0)->data, 300u);
}

TEST(EmulatedDrive, SdoServerAbortsEveryRefusedAccess) {
  DriveRig rig;
  rig.run(1e-3);
  EXPECT_EQ(abort_of(rig.sdo_read(0x2100, 0)), sdo_abort::kNoObject);
  EXPECT_EQ(abort_of(rig.sdo_read(0x1018, 7)), sdo_abort::kNoSubindex);
  EXPECT_EQ(abort_of(rig.sdo_read(0x1800, 4)), sdo_abort::kNoSubindex);
  EXPECT_EQ(abort_of(rig.sdo_read(0x1400, 5)), sdo_abort::kNoSubindex);
  EXPECT_EQ(abort_of(rig.sdo_write(od::kStatusword, 0, 0, 2)), sdo_abort::kReadOnly);
  EXPECT_EQ(abort_of(rig.sdo_write(0x1000, 0, 0, 4)), sdo_abort::kReadOnly);
  EXPECT_EQ(abort_of(rig.sdo_write(od::kControlword, 0, 6, 4)), sdo_abort::kLengthTooHigh);
  EXPECT_EQ(abort_of(rig.sdo_write(od::kTargetPosition, 0, 6, 2)), sdo_abort::kLengthTooLow);
  EXPECT_EQ(abort_of(rig.sdo_write(od::kModesOfOperation, 0, 3, 1)), sdo_abort::kInvalidValue);
  EXPECT_EQ(abort_of(rig.sdo_write(od::kMaxCurrent, 0, 5000, 2)), sdo_abort::kValueTooHigh);  // peak 3 A
  EXPECT_EQ(abort_of(rig.sdo_write(0x1800, 2, 252, 1)), sdo_abort::kInvalidValue);            // RTR-only types
  // a segmented download: the server only does expedited transfers
  CanFrame segmented = *encode_sdo_download_request(rig.node(), 0x1008, 0, 0, 4);
  segmented.data[0] = 0x21;
  EXPECT_EQ(abort_of(rig.sdo(segmented)), sdo_abort::kInvalidCommand);
  // an SDO frame that is not 8 bytes is not answered at all
  CanFrame short_frame = *encode_sdo_upload_request(rig.node(), 0x1000, 0);
  short_frame.dlc = 4;
  EXPECT_FALSE(rig.sdo(short_frame).ok());
  EXPECT_EQ(rig.drive().stats().malformed_frames, 1u);
}

TEST(EmulatedDrive, SdoServerIsSilentWhenStopped) {
  DriveRig rig;
  rig.run(1e-3);
  rig.send(encode_nmt(NmtCommand::kStop, rig.node()));
  rig.run(1e-3);
  EXPECT_FALSE(rig.sdo_read(0x1000, 0).ok());
  rig.send(encode_nmt(NmtCommand::kEnterPreOperational, rig.node()));
  rig.run(1e-3);
  EXPECT_TRUE(rig.sdo_read(0x1000, 0).ok());
}

// --- CiA 402 and cyclic synchronous position --------------------------------------------------------

TEST(EmulatedDrive, MasterHelperWalksDriveToOperationEnabled) {
  DriveRig rig;
  EXPECT_EQ(rig.bring_up(), 3);  // shutdown, switch on, enable operation
  EXPECT_EQ(rig.drive().state(), State::kOperationEnabled);
  const uint16_t sw = rig.last_feedback().statusword;
  EXPECT_EQ(cia402::state_from_statusword(sw), State::kOperationEnabled);
  EXPECT_TRUE(sw & cia402::sw::kDriveFollowsCommand);
  EXPECT_EQ(rig.sdo_read(od::kModesOfOperationDisplay, 0)->data, 8u);
  // enabled without a new target: the link holds its position
  for (int i = 0; i < 50; ++i) rig.cycle(0x000F, rig.drive().target_ticks(), 4e-3);
  EXPECT_NEAR(rig.drive().position_rad(), 0.0, 1e-3);
}

TEST(EmulatedDrive, TracksPositionStepWithin300MsTo2Mrad) {
  DriveRig rig;
  ASSERT_GT(rig.bring_up(), 0);
  const double step_rad = 0.5;
  const int32_t target = ticks(rig, step_rad);
  double overshoot = 0;
  // the bus budget's cycle: 250 Hz
  for (int i = 0; i < 75; ++i) {  // 300 ms
    rig.cycle(0x000F, target, 4e-3);
    overshoot = std::max(overshoot, rig.drive().position_rad() - step_rad);
  }
  EXPECT_NEAR(rig.drive().position_rad(), step_rad, 2e-3);
  EXPECT_LT(overshoot, 0.02);
  EXPECT_LT(std::fabs(rig.drive().velocity_radps()), 0.05);
  // what the master sees agrees with the link to a few ticks
  EXPECT_NEAR(rig.last_feedback().position_ticks, rig.drive().position_ticks(), 200);
  EXPECT_NEAR(rig.last_feedback().position_ticks / rig.drive().ticks_per_rad(), step_rad, 3e-3);
}

TEST(EmulatedDrive, RespectsCurrentLimitOnLargeStep) {
  DriveRig rig;
  ASSERT_GT(rig.bring_up(), 0);
  rig.write(od::kMaxCurrent, 0, 300, 2);  // 0.3 A of 1 A rated
  EXPECT_NEAR(rig.drive().current_limit_a(), 0.3, 1e-12);
  const int32_t target = ticks(rig, 0.8);
  double max_current = 0;
  int max_reported = 0;
  bool limit_flag = false;
  for (int i = 0; i < 1000; ++i) {  // 1 s at 1 kHz
    const auto fb = rig.cycle(0x000F, target, 1e-3);
    max_current = std::max(max_current, std::fabs(rig.drive().current_a()));
    if (fb) {
      max_reported = std::max(max_reported, std::abs(int{fb->current_permille}));
      limit_flag = limit_flag || (fb->statusword & cia402::sw::kInternalLimitActive);
    }
  }
  EXPECT_LE(max_current, 0.3 * 1.02);
  EXPECT_GE(max_current, 0.3 * 0.9);  // the limit was actually reached
  EXPECT_LE(max_reported, 306);
  EXPECT_TRUE(limit_flag);
  EXPECT_NEAR(rig.drive().position_rad(), 0.8, 5e-3);  // and still arrives
}

TEST(EmulatedDrive, HardStopStallsTheLinkAtTheCurrentLimit) {
  DriveRig rig;
  ASSERT_GT(rig.bring_up(), 0);
  const double stop = EmulatedMotorParams{}.stop_max_rad;         // 1.2 rad
  const int32_t beyond = ticks(rig, stop + 0.1);                  // within the following-error window
  for (int i = 0; i < 500; ++i) rig.cycle(0x000F, beyond, 4e-3);  // 2 s
  EXPECT_GE(rig.drive().position_rad(), stop);
  EXPECT_LE(rig.drive().position_rad(), stop + 0.02);
  EXPECT_LT(std::fabs(rig.drive().velocity_radps()), 0.01);
  // the signature a current-threshold homing looks for: full current, no motion
  EXPECT_GE(std::fabs(rig.drive().current_a()), 0.95 * rig.drive().current_limit_a());
  EXPECT_GE(rig.last_feedback().current_permille, 1400);
  EXPECT_TRUE(rig.last_feedback().statusword & cia402::sw::kInternalLimitActive);
  EXPECT_EQ(rig.drive().state(), State::kOperationEnabled);
  EXPECT_TRUE(emcys(rig).empty());
}

TEST(EmulatedDrive, GainsObjectWritesTheControllerAsReal32) {
  DriveRig rig;
  rig.run(1e-3);
  rig.write(drive_od::kGains, drive_od::gain::kPositionKp, drive_od::real32_bits(12.5), 4);
  EXPECT_DOUBLE_EQ(rig.drive().config().control.position_kp_a_per_rad, 12.5);
  const auto r = rig.sdo_read(drive_od::kGains, drive_od::gain::kCurrentKi);
  ASSERT_TRUE(r.ok());
  EXPECT_FLOAT_EQ(static_cast<float>(drive_od::real32_value(r->data)), 12566.0f);
  const auto negative = rig.sdo_write(drive_od::kGains, drive_od::gain::kPositionKi, drive_od::real32_bits(-1.0), 4);
  ASSERT_TRUE(negative.ok());
  EXPECT_EQ(negative->abort_code, sdo_abort::kValueTooLow);
  const auto nan = rig.sdo_write(drive_od::kGains, drive_od::gain::kPositionKd, 0x7FC00000u, 4);
  ASSERT_TRUE(nan.ok());
  EXPECT_EQ(nan->abort_code, sdo_abort::kInvalidValue);
  const auto missing = rig.sdo_read(drive_od::kGains, 8);
  ASSERT_TRUE(missing.ok());
  EXPECT_EQ(missing->abort_code, sdo_abort::kNoSubindex);
}

TEST(EmulatedDrive, FaultInjectionObjectActsLikeTheInjectionCalls) {
  DriveRig rig;
  rig.bring_up();
  rig.write(drive_od::kFaultInjection, drive_od::inject::kSuppressHeartbeat, 1, 4);
  rig.clear_received();
  rig.run(0.3);
  EXPECT_TRUE(rig.frames(0x700u + rig.node()).empty());
  rig.write(drive_od::kFaultInjection, drive_od::inject::kSuppressHeartbeat, 0, 4);
  rig.write(drive_od::kFaultInjection, drive_od::inject::kRefuseSdo, 1, 4);
  const auto refused = rig.sdo_read(0x1000, 0);
  ASSERT_TRUE(refused.ok());
  EXPECT_EQ(refused->abort_code, sdo_abort::kLocalControl);
  rig.write(drive_od::kFaultInjection, drive_od::inject::kRefuseSdo, 0, 4);
  rig.write(drive_od::kFaultInjection, drive_od::inject::kRaiseFault, emcy::kOverCurrent, 4);
  rig.run(0.01);
  EXPECT_EQ(rig.drive().state(), State::kFault);
  EXPECT_EQ(rig.drive().error_code(), emcy::kOverCurrent);
}

TEST(EmulatedDrive, RpdoTargetTakesEffectAtTheNextSync) {
  DriveRig rig;
  ASSERT_GT(rig.bring_up(), 0);
  const uint64_t values[] = {0x000F, 4242};
  rig.send(encode_pdo(rpdo_cob_id(1, rig.node()), default_rpdo1(), values));
  rig.run(2e-3);
  EXPECT_NE(rig.drive().target_ticks(), 4242);
  rig.send(encode_sync());
  rig.run(1e-3);
  EXPECT_EQ(rig.drive().target_ticks(), 4242);
}

TEST(EmulatedDrive, QuickStopHoldsPositionAndHelperReenables) {
  DriveRig rig;
  ASSERT_GT(rig.bring_up(), 0);
  const int32_t target = ticks(rig, 1.0);
  for (int i = 0; i < 25; ++i) rig.cycle(0x000F, target, 4e-3);  // moving at ~3 rad/s
  const double q_at_stop = rig.drive().position_rad();
  ASSERT_GT(rig.drive().velocity_radps(), 1.0);
  rig.cycle(0x0002, target, 4e-3);
  EXPECT_EQ(rig.drive().state(), State::kQuickStopActive);
  for (int i = 0; i < 50; ++i) rig.cycle(0x0002, target, 4e-3);
  EXPECT_NEAR(rig.drive().position_rad(), q_at_stop, 0.05);  // braked, not at the target
  EXPECT_LT(std::fabs(rig.drive().velocity_radps()), 0.01);
  EXPECT_GT(rig.enable(), 0);
}

// --- determinism and real-time discipline -----------------------------------------------------------

std::vector<CanFrame> scripted_run() {
  DriveRig rig;
  std::vector<CanFrame> all;
  (void)rig.bring_up();
  all = rig.received();
  for (int i = 0; i < 100; ++i) {
    rig.cycle(0x000F, static_cast<int32_t>(20000 * std::sin(0.05 * i)), 4e-3);
    all.insert(all.end(), rig.received().begin(), rig.received().end());
  }
  rig.drive().raise_fault(emcy::kMotorBlocked);
  rig.enable();
  rig.run(0.5);
  all.insert(all.end(), rig.received().begin(), rig.received().end());
  return all;
}

TEST(EmulatedDrive, SameScriptGivesIdenticalFrames) {
  const auto a = scripted_run();
  const auto b = scripted_run();
  ASSERT_EQ(a.size(), b.size());
  ASSERT_GT(a.size(), 100u);
  for (size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i], b[i]) << i;
}

TEST(EmulatedDrive, StepDoesNotAllocate) {
  DriveRig rig;
  ASSERT_GT(rig.bring_up(), 0);
  const int32_t target = ticks(rig, 0.3);
  const uint64_t values[] = {0x000F, static_cast<uint32_t>(target)};
  const CanFrame rpdo = *encode_pdo(rpdo_cob_id(1, rig.node()), default_rpdo1(), values);
  const CanFrame sync = *encode_sync();
  const CanFrame sdo = *encode_sdo_upload_request(rig.node(), od::kStatusword, 0);
  {
    ::teleop::test::ScopedAllocationCounter counter;
    for (int i = 0; i < 200; ++i) {
      ASSERT_EQ(rig.master().send(rpdo), CanStatus::kOk);
      ASSERT_EQ(rig.master().send(sync), CanStatus::kOk);
      if (i % 10 == 0) {
        ASSERT_EQ(rig.master().send(sdo), CanStatus::kOk);
      }
      if (i == 100) rig.drive().raise_fault(emcy::kOverCurrent);
      rig.drive().step(1e-3);
    }
    EXPECT_EQ(counter.count(), 0u);
  }
  EXPECT_GT(rig.drive().stats().tpdos_sent, 150u);
}

TEST(EmulatedDrive, RejectsInvalidConfiguration) {
  VirtualCanBus bus;
  auto ep = bus.open();
  auto make = [&](auto edit) {
    EmulatedDriveConfig c;
    edit(c);
    EmulatedDrive d(*ep, c);
  };
  EXPECT_THROW(make([](EmulatedDriveConfig& c) { c.node_id = 0; }), std::invalid_argument);
  EXPECT_THROW(make([](EmulatedDriveConfig& c) { c.node_id = 128; }), std::invalid_argument);
  EXPECT_THROW(make([](EmulatedDriveConfig& c) { c.motor.stop_min_rad = 2.0; }), std::invalid_argument);
  EXPECT_THROW(make([](EmulatedDriveConfig& c) { c.motor.inductance_h = 0; }), std::invalid_argument);
  EXPECT_THROW(make([](EmulatedDriveConfig& c) { c.max_current_a = 5.0; }), std::invalid_argument);
  EXPECT_THROW(make([](EmulatedDriveConfig& c) { c.initial_position_rad = 3.0; }), std::invalid_argument);
  EXPECT_THROW(make([](EmulatedDriveConfig& c) { c.control.position_loop_divider = 0; }), std::invalid_argument);
  EXPECT_NO_THROW(make([](EmulatedDriveConfig&) {}));
}

}  // namespace
}  // namespace teleop::drive::test
