// The emulated drive as a joint drive of a torque-controlled arm: cyclic synchronous torque
// (mode 10) with the targets and feedback a master maps by SDO, the rated torque that is the unit
// of both, and the drive's own reaction to a lost master: the heartbeat it consumes (0x1016)
// times out and 0x6007 selects what it does.
#include <gtest/gtest.h>

#include <cmath>
#include <initializer_list>
#include <optional>

#include "drive_rig.h"

namespace teleop::drive::test {
namespace {

using namespace can;  // the CANopen core the drive is built on
namespace od = cia402::od;
using cia402::State;

/// A link held by a stiff torsional spring: whatever the motor does, it barely moves, and it
/// measures the torque the drive puts out at its gearbox (the mean since the last reset).
class TorqueMeter final : public DrivePlant {
 public:
  double position_rad() const override { return q_rad_; }
  double velocity_radps() const override { return dq_radps_; }
  void apply(double torque_nm, double dt_s, bool jammed) override {
    if (!jammed) {
      dq_radps_ += (torque_nm - kStiffness * q_rad_ - kDamping * dq_radps_) / kInertia * dt_s;
      q_rad_ += dq_radps_ * dt_s;
    }
    impulse_nms_ += torque_nm * dt_s;
    time_s_ += dt_s;
  }
  void reset_mean() { impulse_nms_ = time_s_ = 0.0; }
  double mean_torque_nm() const { return time_s_ > 0 ? impulse_nms_ / time_s_ : 0.0; }

 private:
  static constexpr double kInertia = 0.01, kStiffness = 100.0, kDamping = 2.0;
  double q_rad_ = 0.0, dq_radps_ = 0.0, impulse_nms_ = 0.0, time_s_ = 0.0;
};

constexpr NodeId kMaster = 100;  // the node id of the master's heartbeat
constexpr double kPeriod = 1e-3;  // an arm's cycle

const PdoMapping& torque_rpdo() {
  static const PdoMapping m = *PdoMapping::make({{od::kControlword, 0, 16}, {od::kTargetTorque, 0, 16}});
  return m;
}
// the default TPDO1's layout with torque actual where current actual was
const PdoMapping& torque_tpdo() {
  static const PdoMapping m =
      *PdoMapping::make({{od::kPositionActualValue, 0, 32}, {od::kTorqueActualValue, 0, 16}, {od::kStatusword, 0, 16}});
  return m;
}

struct TorqueFeedback {
  int16_t torque_permille = 0;
  uint16_t statusword = 0;
};

/// Maps a PDO by SDO as a master does it: invalid, entries with the count at 0, count, valid.
void map_pdo(DriveRig& rig, uint16_t communication, uint16_t mapping, uint16_t cob_id, const PdoMapping& entries) {
  rig.write(communication, 1, 0x80000000u | cob_id, 4);
  rig.write(mapping, 0, 0, 1);
  for (size_t k = 0; k < entries.size(); ++k) rig.write(mapping, static_cast<uint8_t>(k + 1), entries[k].to_u32(), 4);
  rig.write(mapping, 0, static_cast<uint32_t>(entries.size()), 1);
  rig.write(communication, 1, cob_id, 4);
}

/// One torque cycle: RPDO1 (controlword, target torque), SYNC, the drive runs one period.
std::optional<TorqueFeedback> torque_cycle(DriveRig& rig, uint16_t controlword, int16_t permille) {
  const uint64_t values[] = {controlword, static_cast<uint16_t>(permille)};
  rig.send(encode_pdo(rpdo_cob_id(1, rig.node()), torque_rpdo(), values));
  rig.send(encode_sync());
  rig.clear_received();
  rig.run(kPeriod);
  std::optional<TorqueFeedback> fb;
  for (const CanFrame& f : rig.frames(tpdo_cob_id(1, rig.node()))) {
    uint64_t v[3];
    if (decode_pdo(f, torque_tpdo(), v) == CanError::kNone) {
      fb = TorqueFeedback{static_cast<int16_t>(sign_extend(v[1], 16)), static_cast<uint16_t>(v[2])};
    }
  }
  return fb;
}

/// Boots the drive, maps the torque PDOs, selects CST and walks it to operation enabled at zero
/// torque: the cycles it took, or -1.
int bring_up_torque(DriveRig& rig) {
  rig.run(1e-3);
  map_pdo(rig, 0x1400, 0x1600, rpdo_cob_id(1, rig.node()), torque_rpdo());
  map_pdo(rig, 0x1800, 0x1A00, tpdo_cob_id(1, rig.node()), torque_tpdo());
  rig.write(od::kModesOfOperation, 0, static_cast<uint8_t>(cia402::kModeCyclicSynchronousTorque), 1);
  rig.send(encode_nmt(NmtCommand::kStart, rig.node()));
  rig.run(1e-3);
  uint16_t cw = 0;
  uint16_t statusword = rig.drive().statusword();
  for (int i = 1; i <= 20; ++i) {
    cw = cia402::next_controlword(statusword, cw);
    const auto fb = torque_cycle(rig, cw, 0);
    if (!fb) return -1;
    statusword = fb->statusword;
    if (cia402::state_from_statusword(statusword) == State::kOperationEnabled) return i;
  }
  return -1;
}

/// The output torque a target makes: per mille of the rated torque, through gearbox and efficiency.
double output_torque_nm(const EmulatedDriveConfig& config, int16_t permille, double rated_torque_nm) {
  return permille * 1e-3 * rated_torque_nm * config.motor.gear_ratio * config.motor.gear_efficiency;
}

TEST(EmulatedDriveTorque, DrivesTheTargetTorqueThroughTheGearboxAndReportsIt) {
  const EmulatedDriveConfig config;
  TorqueMeter meter;
  DriveRig rig(config, meter);
  ASSERT_GT(bring_up_torque(rig), 0);
  // 0x6076 is k_t x rated current: 0.01 N m/A x 1 A = 10 mN m
  const auto rated = rig.sdo_read(od::kMotorRatedTorque, 0);
  ASSERT_TRUE(rated.ok());
  EXPECT_EQ(rated->data, 10u);
  EXPECT_DOUBLE_EQ(rig.drive().rated_torque_nm(), 0.010);

  for (const int16_t permille : {500, -800, 250}) {
    for (int i = 0; i < 20; ++i) torque_cycle(rig, 0x000F, permille);  // the current loop settles in ~2 ms
    meter.reset_mean();
    std::optional<TorqueFeedback> fb;
    for (int i = 0; i < 50; ++i) fb = torque_cycle(rig, 0x000F, permille);
    ASSERT_TRUE(fb);
    const double expected = output_torque_nm(config, permille, rig.drive().rated_torque_nm());
    EXPECT_NEAR(meter.mean_torque_nm(), expected, 0.01 * std::fabs(expected)) << permille;
    EXPECT_NEAR(fb->torque_permille, permille, 10) << "torque actual 0x6077";
    EXPECT_TRUE(fb->statusword & cia402::sw::kDriveFollowsCommand);
    EXPECT_FALSE(fb->statusword & cia402::sw::kInternalLimitActive);
  }
}

TEST(EmulatedDriveTorque, ATargetBeyondTheCurrentLimitIsClampedAndFlagged) {
  const EmulatedDriveConfig config;  // 0x6073 = 1.5 x rated current
  TorqueMeter meter;
  DriveRig rig(config, meter);
  ASSERT_GT(bring_up_torque(rig), 0);
  for (int i = 0; i < 20; ++i) torque_cycle(rig, 0x000F, 3000);
  meter.reset_mean();
  std::optional<TorqueFeedback> fb;
  for (int i = 0; i < 50; ++i) fb = torque_cycle(rig, 0x000F, 3000);
  ASSERT_TRUE(fb);
  EXPECT_NEAR(meter.mean_torque_nm(), output_torque_nm(config, 1500, 0.010), 0.015);
  EXPECT_NEAR(fb->torque_permille, 1500, 15);
  EXPECT_TRUE(fb->statusword & cia402::sw::kInternalLimitActive);
}

TEST(EmulatedDriveTorque, RefusesWhatItCannotDo) {
  DriveRig rig;
  rig.run(1e-3);
  EXPECT_EQ(abort_of(rig.sdo_write(od::kModesOfOperation, 0, 9, 1)), sdo_abort::kInvalidValue);  // CSV
  EXPECT_EQ(abort_of(rig.sdo_write(od::kAbortConnectionOptionCode, 0, 4, 2)), sdo_abort::kInvalidValue);
  EXPECT_EQ(abort_of(rig.sdo_write(od::kAbortConnectionOptionCode, 0, 0xFFFF, 2)), sdo_abort::kInvalidValue);
  EXPECT_EQ(abort_of(rig.sdo_write(od::kMotorRatedTorque, 0, 20, 4)), sdo_abort::kReadOnly);
  // its quick stop brakes and holds in quick stop active (code 6): that, and only that, is accepted
  EXPECT_EQ(abort_of(rig.sdo_write(od::kQuickStopOptionCode, 0, 2, 2)), sdo_abort::kInvalidValue);
  rig.write(od::kQuickStopOptionCode, 0, cia402::kQuickStopRampAndHold, 2);
  EXPECT_EQ(rig.sdo_read(od::kQuickStopOptionCode, 0)->data, 6u);
  // one node watched twice
  rig.write(obj::kConsumerHeartbeatTime, 1, consumer_heartbeat_entry(kMaster, 50), 4);
  EXPECT_EQ(abort_of(rig.sdo_write(obj::kConsumerHeartbeatTime, 2, consumer_heartbeat_entry(kMaster, 80), 4)),
            sdo_abort::kParameterIncompatible);
  rig.write(obj::kConsumerHeartbeatTime, 2, consumer_heartbeat_entry(kMaster + 1, 80), 4);
  EXPECT_EQ(rig.sdo_read(obj::kConsumerHeartbeatTime, 2)->data, consumer_heartbeat_entry(kMaster + 1, 80));
  EmulatedDriveConfig bad;
  bad.abort_connection_option = 5;
  EXPECT_THROW(DriveRig{bad}, std::invalid_argument);
}

/// A link under a constant load (its weight): it turns unless the motor holds it or it is jammed.
class LoadedLink final : public DrivePlant {
 public:
  double position_rad() const override { return q_rad_; }
  double velocity_radps() const override { return dq_radps_; }
  void apply(double torque_nm, double dt_s, bool jammed) override {
    if (jammed) {
      dq_radps_ = 0.0;
      return;
    }
    dq_radps_ += (torque_nm - 0.1) / 0.01 * dt_s;
    q_rad_ += dq_radps_ * dt_s;
  }

 private:
  double q_rad_ = 0.0, dq_radps_ = 0.0;
};

TEST(EmulatedDriveTorque, AHoldingBrakeHoldsTheLinkWhileThePowerIsOff) {
  EmulatedDriveConfig config;
  config.motor.holding_brake = true;
  LoadedLink link;
  DriveRig rig(config, link);
  rig.run(0.2);  // switch on disabled, braked
  EXPECT_EQ(link.position_rad(), 0.0);
  ASSERT_GT(bring_up_torque(rig), 0);  // enabled at zero torque: the brake lets go, the load turns it
  for (int i = 0; i < 100; ++i) torque_cycle(rig, 0x000F, 0);  // 10 rad/s^2 for 0.1 s
  EXPECT_LT(link.position_rad(), -0.03);
  // disable voltage: braked again where it is
  torque_cycle(rig, 0x0000, 0);
  const double braked_at = link.position_rad();
  rig.run(0.2);
  EXPECT_EQ(link.position_rad(), braked_at);
}

// --- the lost master ---------------------------------------------------------------------------

struct LostMaster {
  double reacted_after_s = -1;  // first step whose state is not operation enabled, after the last heartbeat
  double emcy_after_s = -1;     // the drive's EMCY 0x8130
  double speed_at_reaction_radps = 0;
  State state = State::kUnknown;
};

/// A torque drive watching the master's heartbeat (10 ms period, consumer time 50 ms) with
/// 0x6007 = option, pushing `permille` for 100 ms; then the master dies (no frame at all any more)
/// and the drive runs alone for `silence_s`.
LostMaster lose_master(DriveRig& rig, int16_t option, double silence_s, int16_t permille = 300) {
  LostMaster out;
  rig.run(1e-3);
  rig.write(obj::kConsumerHeartbeatTime, 1, consumer_heartbeat_entry(kMaster, 50), 4);
  rig.write(od::kAbortConnectionOptionCode, 0, static_cast<uint16_t>(option), 2);
  EXPECT_GT(bring_up_torque(rig), 0);
  for (int i = 0; i < 100; ++i) {
    if (i % 10 == 0) rig.send(encode_heartbeat(kMaster, NmtState::kOperational));
    torque_cycle(rig, 0x000F, permille);
  }
  rig.send(encode_heartbeat(kMaster, NmtState::kOperational));
  rig.clear_received();
  const double last_heartbeat_s = rig.drive().time_s();
  for (double t = 0; t < silence_s; t += kPeriod) {
    rig.run(kPeriod);
    const double after = rig.drive().time_s() - last_heartbeat_s;
    if (out.reacted_after_s < 0 && rig.drive().state() != State::kOperationEnabled) {
      out.reacted_after_s = after;
      out.speed_at_reaction_radps = std::fabs(rig.drive().velocity_radps());
    }
    if (out.emcy_after_s < 0) {
      for (const EmcyMessage& m : emcys(rig)) {
        if (m.error_code == emcy::kHeartbeatError) out.emcy_after_s = after;
      }
    }
  }
  out.state = rig.drive().state();
  return out;
}

TEST(EmulatedDriveTorque, ALostMasterQuickStopsTheDriveWithinTheConsumerTimeAndItStaysStopped) {
  DriveRig rig;  // its own free link: 20 per mille spin it up to about 1 rad/s
  const LostMaster lost = lose_master(rig, cia402::abort_connection::kQuickStop, 0.2, 20);
  // silent for more than 50 ms: seen at the end of the first 1 ms step past it
  EXPECT_GT(lost.emcy_after_s, 0.050);
  EXPECT_LE(lost.emcy_after_s, 0.052);
  EXPECT_DOUBLE_EQ(lost.reacted_after_s, lost.emcy_after_s);
  // the dead master's last controlword (enable operation) does not undo the quick stop
  EXPECT_EQ(lost.state, State::kQuickStopActive);
  EXPECT_EQ(rig.drive().stats().heartbeat_timeouts, 1u);
  // it braked the link and holds it (no longer pushed, it would coast on for ~0.1 s)
  EXPECT_GT(lost.speed_at_reaction_radps, 0.5);
  const double held_rad = rig.drive().position_rad();
  EXPECT_LT(std::fabs(rig.drive().velocity_radps()), 0.01);
  rig.run(0.2);
  EXPECT_NEAR(rig.drive().position_rad(), held_rad, 1e-3);
  // the master comes back: its heartbeat, then the walk from quick stop to enabled
  rig.send(encode_heartbeat(kMaster, NmtState::kOperational));
  uint16_t cw = 0x0002;
  for (int i = 0; i < 20 && rig.drive().state() != State::kOperationEnabled; ++i) {
    cw = cia402::next_controlword(rig.drive().statusword(), cw);
    torque_cycle(rig, cw, 0);
  }
  EXPECT_EQ(rig.drive().state(), State::kOperationEnabled);
}

TEST(EmulatedDriveTorque, TheAbortConnectionOptionSelectsTheReaction) {
  {
    DriveRig rig;
    const LostMaster lost = lose_master(rig, cia402::abort_connection::kFault, 0.1);
    EXPECT_EQ(lost.state, State::kFault);
    EXPECT_EQ(rig.drive().error_code(), emcy::kHeartbeatError);
    EXPECT_GT(lost.emcy_after_s, 0.050);
  }
  {
    DriveRig rig;
    const LostMaster lost = lose_master(rig, cia402::abort_connection::kDisableVoltage, 0.1);
    EXPECT_EQ(lost.state, State::kSwitchOnDisabled);
    EXPECT_NEAR(rig.drive().current_a(), 0.0, 1e-3);  // power off: the current died out
  }
  {
    DriveRig rig;
    const LostMaster lost = lose_master(rig, cia402::abort_connection::kNoAction, 0.1);
    EXPECT_EQ(lost.state, State::kOperationEnabled);  // as configured: it keeps pushing
    EXPECT_GT(lost.emcy_after_s, 0.050);              // but says so
  }
}

TEST(EmulatedDriveTorque, TheWatchStartsWithTheMastersFirstHeartbeat) {
  DriveRig rig;
  rig.run(1e-3);
  rig.write(obj::kConsumerHeartbeatTime, 1, consumer_heartbeat_entry(kMaster, 50), 4);
  rig.write(od::kAbortConnectionOptionCode, 0, cia402::abort_connection::kQuickStop, 2);
  ASSERT_GT(bring_up_torque(rig), 0);
  rig.run(0.5);  // no heartbeat ever: nothing to miss yet
  EXPECT_EQ(rig.drive().state(), State::kOperationEnabled);
  EXPECT_EQ(rig.drive().stats().heartbeat_timeouts, 0u);
}

}  // namespace
}  // namespace teleop::drive::test
