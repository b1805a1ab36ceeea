// The emulated CiA 402 drive on a VirtualCanBus, driven by a test master: PDO configuration
// (mapping rules, dummy entries, transmission types, event timers) and every fault injection
// hook producing the right frames.
#include "teleop/drive/emulated_drive.h"

#include <gtest/gtest.h>

#include "drive_rig.h"

namespace teleop::drive::test {

using namespace can;  // the CANopen core the drive is built on

namespace {

// --- PDO configuration ------------------------------------------------------------------------------

TEST(EmulatedDrive, EnforcesPdoMappingRules) {
  DriveRig rig;
  rig.run(1e-3);
  // a valid PDO's mapping and COB-ID cannot change
  EXPECT_EQ(abort_of(rig.sdo_write(0x1600, 0, 0, 1)), sdo_abort::kUnsupportedAccess);
  EXPECT_EQ(abort_of(rig.sdo_write(0x1400, 1, 0x222, 4)), sdo_abort::kInvalidValue);
  EXPECT_EQ(abort_of(rig.sdo_write(0x1400, 1, 0x20000201, 4)), sdo_abort::kInvalidValue);  // 29-bit
  rig.write(0x1400, 1, 0x80000201, 4);                                                     // disable RPDO1
  for (uint32_t restricted : {0x000u, 0x080u, 0x5FFu, 0x605u, 0x701u}) {
    EXPECT_EQ(abort_of(rig.sdo_write(0x1400, 1, restricted, 4)), sdo_abort::kInvalidValue) << std::hex << restricted;
  }
  EXPECT_EQ(abort_of(rig.sdo_write(0x1600, 1, 0x60410010, 4)), sdo_abort::kUnsupportedAccess);  // sub 0 != 0
  rig.write(0x1600, 0, 0, 1);
  rig.write(0x1600, 1, 0x60410010, 4);  // statusword: transmit-only
  EXPECT_EQ(abort_of(rig.sdo_write(0x1600, 0, 1, 1)), sdo_abort::kNotMappable);
  rig.write(0x1600, 1, 0x607A0010, 4);  // target position with the wrong length
  EXPECT_EQ(abort_of(rig.sdo_write(0x1600, 0, 1, 1)), sdo_abort::kNotMappable);
  rig.write(0x1600, 1, 0x607A0020, 4);
  rig.write(0x1600, 2, 0x607A0020, 4);
  rig.write(0x1600, 3, 0x60400010, 4);
  EXPECT_EQ(abort_of(rig.sdo_write(0x1600, 0, 3, 1)), sdo_abort::kMappingTooLong);  // 80 bits
  EXPECT_EQ(abort_of(rig.sdo_write(0x1600, 0, 9, 1)), sdo_abort::kMappingTooLong);
  rig.write(0x1600, 0, 2, 1);
  EXPECT_EQ(rig.sdo_read(0x1600, 0)->data, 2u);
  // a dummy entry only makes sense in a received PDO
  rig.write(0x1800, 1, 0x80000181, 4);
  rig.write(0x1A00, 0, 0, 1);
  rig.write(0x1A00, 1, kDummy32.to_u32(), 4);
  EXPECT_EQ(abort_of(rig.sdo_write(0x1A00, 0, 1, 1)), sdo_abort::kNotMappable);
}

TEST(EmulatedDrive, GroupRpdoWithDummyMappingDrivesTwoNodes) {
  VirtualCanBus bus;
  auto master = bus.open("master");
  auto ep1 = bus.open("node1");
  auto ep2 = bus.open("node2");
  EmulatedDriveConfig c1;
  c1.node_id = 1;
  EmulatedDriveConfig c2;
  c2.node_id = 2;
  EmulatedDrive d1(*ep1, c1);
  EmulatedDrive d2(*ep2, c2);
  auto step = [&] {
    d1.step(1e-3);
    d2.step(1e-3);
    CanFrame f;
    while (master->receive(f, std::chrono::nanoseconds::zero()) == CanStatus::kOk) {
      if (f.id == 0x581u || f.id == 0x582u) {
        const auto r = decode_sdo_response(f);
        ASSERT_TRUE(r.ok());
        ASSERT_EQ(r->type, SdoType::kDownloadResponse) << std::hex << r->abort_code;
      }
    }
  };
  auto write = [&](NodeId node, uint16_t index, uint8_t sub, uint32_t value, uint8_t size) {
    ASSERT_EQ(master->send(*encode_sdo_download_request(node, index, sub, value, size)), CanStatus::kOk);
    step();
  };
  step();  // boot
  // both nodes listen to one RPDO on 0x301: node 1 takes bytes 0..3, node 2 bytes 4..7
  const uint32_t maps[2][2] = {{0x607A0020, kDummy32.to_u32()}, {kDummy32.to_u32(), 0x607A0020}};
  for (NodeId node : {NodeId{1}, NodeId{2}}) {
    write(node, 0x1601, 0, 0, 1);
    write(node, 0x1601, 1, maps[node - 1][0], 4);
    write(node, 0x1601, 2, maps[node - 1][1], 4);
    write(node, 0x1601, 0, 2, 1);
    write(node, 0x1401, 1, 0x301, 4);
  }
  ASSERT_EQ(master->send(*encode_nmt(NmtCommand::kStart, 0)), CanStatus::kOk);
  step();
  const auto packed = *PdoMapping::make({{0x607A, 0, 32}, {0x607A, 0, 32}});
  const uint64_t targets[] = {11111, static_cast<uint32_t>(-22222)};
  ASSERT_EQ(master->send(*encode_pdo(0x301, packed, targets)), CanStatus::kOk);
  ASSERT_EQ(master->send(*encode_sync()), CanStatus::kOk);
  step();
  EXPECT_EQ(d1.target_ticks(), 11111);
  EXPECT_EQ(d2.target_ticks(), -22222);
}

TEST(EmulatedDrive, TpdoTransmissionTypeTwoSendsOnEverySecondSync) {
  DriveRig rig;
  rig.run(1e-3);
  rig.write(0x1800, 2, 2, 1);
  rig.send(encode_nmt(NmtCommand::kStart, rig.node()));
  rig.run(1e-3);
  int tpdos = 0;
  for (int i = 0; i < 6; ++i) {
    rig.send(encode_sync());
    rig.clear_received();
    rig.run(1e-3);
    tpdos += static_cast<int>(rig.frames(0x181).size());
  }
  EXPECT_EQ(tpdos, 3);
}

TEST(EmulatedDrive, EventDrivenTpdoFollowsItsEventTimer) {
  DriveRig rig;
  rig.run(1e-3);
  rig.write(0x1801, 2, 255, 1);
  rig.write(0x1801, 5, 10, 2);     // every 10 ms
  rig.write(0x1801, 1, 0x281, 4);  // TPDO2: velocity actual, error code
  rig.send(encode_nmt(NmtCommand::kStart, rig.node()));
  rig.run(1e-3);
  rig.clear_received();
  rig.run(0.1);
  EXPECT_EQ(rig.frames(0x281).size(), 10u);
  EXPECT_EQ(rig.frames(0x281)[0].dlc, 6);
}

// --- fault injection --------------------------------------------------------------------------------

TEST(EmulatedDrive, InjectedFaultSendsEmcyAndReportsFault) {
  DriveRig rig;
  ASSERT_GT(rig.bring_up(), 0);
  rig.clear_received();
  rig.drive().raise_fault(emcy::kOverCurrent, {1, 2, 3, 4, 5});
  rig.drain();
  const auto e = emcys(rig);
  ASSERT_EQ(e.size(), 1u);
  EXPECT_EQ(e[0].node, rig.node());
  EXPECT_EQ(e[0].error_code, emcy::kOverCurrent);
  EXPECT_EQ(e[0].error_register, 0x03);  // generic + current
  EXPECT_EQ(e[0].vendor, (std::array<uint8_t, 5>{1, 2, 3, 4, 5}));
  // the TPDO of the next SYNC still shows the fault reaction (2 ms), the one after the fault
  const auto reacting = rig.cycle(0x000F, rig.drive().position_ticks(), 4e-3);
  ASSERT_TRUE(reacting);
  EXPECT_EQ(cia402::state_from_statusword(reacting->statusword), State::kFaultReactionActive);
  const auto fb = rig.cycle(0x000F, rig.drive().position_ticks(), 4e-3);
  ASSERT_TRUE(fb);
  EXPECT_EQ(cia402::state_from_statusword(fb->statusword), State::kFault);
  EXPECT_EQ(rig.drive().current_a(), 0.0);  // power stage off
  EXPECT_EQ(rig.sdo_read(od::kErrorCode, 0)->data, emcy::kOverCurrent);
  EXPECT_EQ(rig.sdo_read(0x1001, 0)->data, 0x03u);
}

TEST(EmulatedDrive, RecoversFromFaultUnderMasterHelper) {
  DriveRig rig;
  ASSERT_GT(rig.bring_up(), 0);
  rig.drive().raise_fault(0x5000);
  rig.cycle(0x000F, rig.drive().position_ticks(), 4e-3);  // reports fault reaction active
  rig.cycle(0x000F, rig.drive().position_ticks(), 4e-3);  // reports fault
  ASSERT_EQ(rig.drive().state(), State::kFault);
  ASSERT_EQ(cia402::state_from_statusword(rig.last_feedback().statusword), State::kFault);
  rig.clear_received();
  std::vector<CanFrame> seen;
  uint16_t cw = 0x000F;
  int cycles = 0;
  for (; cycles < 10 && rig.drive().state() != State::kOperationEnabled; ++cycles) {
    cw = cia402::next_controlword(rig.last_feedback().statusword, cw);
    rig.cycle(cw, rig.drive().position_ticks(), 4e-3);
    seen.insert(seen.end(), rig.received().begin(), rig.received().end());
  }
  EXPECT_EQ(rig.drive().state(), State::kOperationEnabled);
  EXPECT_EQ(cycles, 4);  // fault reset, shutdown, switch on, enable operation
  bool error_reset = false;
  for (const CanFrame& f : seen) {
    if (f.id != static_cast<uint32_t>(cob::kEmcy + rig.node())) continue;
    const auto m = decode_emcy(f);
    error_reset = error_reset || (m.ok() && m->error_code == emcy::kErrorReset && m->error_register == 0);
  }
  EXPECT_TRUE(error_reset);
  EXPECT_EQ(rig.sdo_read(od::kErrorCode, 0)->data, 0u);
}

TEST(EmulatedDrive, StalledMotorEndsInFollowingErrorEmcy) {
  DriveRig rig;
  ASSERT_GT(rig.bring_up(), 0);
  rig.drive().set_stalled(true);
  rig.clear_received();
  const int32_t target = ticks(rig, 0.5);
  const double start = rig.drive().time_s();
  double emcy_after = -1;
  for (int i = 0; i < 500 && emcy_after < 0; ++i) {
    rig.cycle(0x000F, target, 1e-3);
    if (!emcys(rig).empty()) emcy_after = rig.drive().time_s() - start;
  }
  // the ramp reaches the 0.2 rad window after ~67 ms, plus the 100 ms timeout
  EXPECT_GT(emcy_after, 0.15);
  EXPECT_LT(emcy_after, 0.20);
  const auto e = emcys(rig);
  ASSERT_EQ(e.size(), 1u);
  EXPECT_EQ(e[0].error_code, emcy::kFollowingError);
  EXPECT_EQ(e[0].error_register, 0x21);  // generic + device profile
  rig.cycle(0x000F, target, 4e-3);
  const auto fb = rig.cycle(0x000F, target, 4e-3);
  ASSERT_TRUE(fb);
  EXPECT_EQ(cia402::state_from_statusword(fb->statusword), State::kFault);
  EXPECT_TRUE(fb->statusword & cia402::sw::kFollowingError);
  EXPECT_NEAR(rig.drive().position_rad(), 0.0, 1e-6);  // it never moved
}

TEST(EmulatedDrive, SuppressedHeartbeatStopsOnlyTheHeartbeat) {
  DriveRig rig;
  rig.run(1e-3);
  rig.drive().set_heartbeat_suppressed(true);
  rig.clear_received();
  rig.run(1.0);
  EXPECT_TRUE(heartbeats(rig).empty());
  EXPECT_TRUE(rig.sdo_read(0x1000, 0).ok());  // the node is alive otherwise
  rig.drive().set_heartbeat_suppressed(false);
  rig.clear_received();
  rig.run(0.1);
  EXPECT_EQ(heartbeats(rig).size(), 1u);
}

TEST(EmulatedDrive, DroppedTpdosAreMissingForTheirCount) {
  DriveRig rig;
  ASSERT_GT(rig.bring_up(), 0);
  rig.drive().drop_tpdos(3);
  const int32_t hold = rig.drive().position_ticks();
  EXPECT_FALSE(rig.cycle(0x000F, hold, 4e-3));
  EXPECT_FALSE(rig.cycle(0x000F, hold, 4e-3));
  EXPECT_FALSE(rig.cycle(0x000F, hold, 4e-3));
  EXPECT_TRUE(rig.cycle(0x000F, hold, 4e-3));
  EXPECT_EQ(rig.drive().stats().tpdos_dropped, 3u);
  rig.drive().drop_tpdos(EmulatedDrive::kDropForever);
  for (int i = 0; i < 10; ++i) EXPECT_FALSE(rig.cycle(0x000F, hold, 4e-3));
  rig.drive().drop_tpdos(0);
  EXPECT_TRUE(rig.cycle(0x000F, hold, 4e-3));
}

TEST(EmulatedDrive, DelayedTpdosArriveLate) {
  DriveRig rig;
  ASSERT_GT(rig.bring_up(), 0);
  rig.drive().set_tpdo_delay(0.010);
  rig.clear_received();
  rig.send(encode_sync());
  double waited = 0;
  while (rig.frames(tpdo_cob_id(1, rig.node())).empty() && waited < 0.1) {
    rig.run(1e-3);
    waited += 1e-3;
  }
  EXPECT_GE(waited, 0.010 - 1e-9);
  EXPECT_LE(waited, 0.011 + 1e-9);
  rig.drive().set_tpdo_delay(0);
  EXPECT_TRUE(rig.cycle(0x000F, rig.drive().position_ticks(), 1e-3));
}

TEST(EmulatedDrive, DroppedRpdosLeaveTheTargetUnchanged) {
  DriveRig rig;
  ASSERT_GT(rig.bring_up(), 0);
  const int32_t before = rig.drive().target_ticks();
  rig.drive().drop_rpdos(1);
  rig.cycle(0x000F, before + 5000, 4e-3);
  EXPECT_EQ(rig.drive().target_ticks(), before);
  EXPECT_EQ(rig.drive().stats().rpdos_dropped, 1u);
  rig.cycle(0x000F, before + 5000, 4e-3);
  EXPECT_EQ(rig.drive().target_ticks(), before + 5000);
}

TEST(EmulatedDrive, ShortRpdoRaisesPdoLengthEmcyWithoutFault) {
  DriveRig rig;
  ASSERT_GT(rig.bring_up(), 0);
  rig.clear_received();
  CanFrame short_rpdo;
  short_rpdo.id = rpdo_cob_id(1, rig.node());
  short_rpdo.dlc = 4;  // the mapping needs 6
  rig.send_frame(short_rpdo);
  rig.run(1e-3);
  const auto e = emcys(rig);
  ASSERT_EQ(e.size(), 1u);
  EXPECT_EQ(e[0].error_code, emcy::kPdoLengthError);
  EXPECT_TRUE(e[0].error_register & error_register::kCommunication);
  EXPECT_EQ(rig.drive().state(), State::kOperationEnabled);
}

}  // namespace
}  // namespace teleop::drive::test
