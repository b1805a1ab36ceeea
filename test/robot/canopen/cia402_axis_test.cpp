// The master's view of one CiA 402 torque drive: joint units to and from the drive's process
// data, the walk to operation enabled against the drive's state machine, and what counts as a
// failure.
#include "teleop/robot/cia402_axis.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace teleop::robot {
namespace {

namespace cia402 = can::cia402;
using cia402::State;

Cia402AxisConfig joint() {
  Cia402AxisConfig c;
  c.gear_ratio = 100.0;
  c.gear_efficiency = 0.9;
  c.encoder_ticks_per_rev = 4096.0;
  c.rated_torque_nm = 0.5;  // at the motor: 45 N m at the joint
  c.offset_rad = 0.25;
  c.max_torque_nm = 80.0;
  return c;
}

TEST(Cia402Axis, TurnsTicksAndPerMilleIntoJointUnits) {
  Cia402Axis axis(joint());
  const double ticks_per_rad = 4096.0 * 100.0 / (2 * M_PI);
  axis.take({0, static_cast<int32_t>(std::lround(1.0 * ticks_per_rad)), 500, true,
             static_cast<int32_t>(std::lround(-2.0 * ticks_per_rad))});
  EXPECT_NEAR(axis.position_rad(), 1.25, 1e-5);  // offset + 1 rad
  EXPECT_NEAR(axis.velocity_radps(), -2.0, 1e-5);
  EXPECT_NEAR(axis.torque_nm(), 0.5 * 0.5 * 100 * 0.9, 1e-9);  // 500 per mille of 45 N m
}

TEST(Cia402Axis, DifferentiatesPositionsWhereTheBusCarriesNoVelocity) {
  Cia402Axis axis(joint());
  const double ticks_per_rad = 4096.0 * 100.0 / (2 * M_PI);
  axis.take({0, 0, 0});
  EXPECT_EQ(axis.velocity_radps(), 0.0);
  // 0.5 rad/s sampled every 1 ms: the filter (200 Hz) settles within ~5 ms
  for (int k = 1; k <= 20; ++k) axis.take({0, static_cast<int32_t>(std::lround(0.5 * k * 1e-3 * ticks_per_rad)), 0}, 1e-3);
  EXPECT_NEAR(axis.velocity_radps(), 0.5, 0.01);
  axis.take({0, static_cast<int32_t>(std::lround(0.5 * 20 * 1e-3 * ticks_per_rad)), 0}, 0.0);  // the same sample
  EXPECT_NEAR(axis.velocity_radps(), 0.5, 0.01);
}

TEST(Cia402Axis, AnInvertedJointTurnsAgainstTheMotor) {
  Cia402AxisConfig c = joint();
  c.inverted = true;
  Cia402Axis axis(c);
  axis.take({0, 65190, 100, true, 65190});
  EXPECT_NEAR(axis.position_rad(), 0.25 - 1.0, 1e-4);
  EXPECT_LT(axis.velocity_radps(), 0);
  EXPECT_LT(axis.torque_nm(), 0);
  bool clamped = true;
  EXPECT_EQ(axis.torque_permille(-4.5, clamped), 100);
  EXPECT_FALSE(clamped);
}

TEST(Cia402Axis, ClampsTorqueToTheJointsLimitAndCountsIt) {
  Cia402Axis axis(joint());
  bool clamped = true;
  EXPECT_EQ(axis.torque_permille(22.5, clamped), 500);
  EXPECT_FALSE(clamped);
  EXPECT_EQ(axis.torque_permille(200.0, clamped), 1778);  // 80 N m / 0.045 N m per per mille
  EXPECT_TRUE(clamped);
  EXPECT_EQ(axis.torque_permille(-200.0, clamped), -1778);
  EXPECT_TRUE(clamped);
  // a limit beyond what INTEGER16 can say is clamped there too
  Cia402AxisConfig big = joint();
  big.max_torque_nm = 1e4;
  EXPECT_EQ(Cia402Axis(big).torque_permille(5e3, clamped), 32767);
  EXPECT_TRUE(clamped);
}

// the drive's side of the walk, by CiA 402's own state machine (teleop/can/cia402.h)
struct DriveStateMachine {
  State state = State::kSwitchOnDisabled;
  uint16_t previous = 0;
  AxisFeedback feedback() const { return {cia402::statusword_for(state), 0, 0}; }
  void obey(uint16_t controlword) {
    state = cia402::next_state(state, cia402::command_from_controlword(controlword, previous));
    previous = controlword;
  }
};

/// Walks the drive with the axis's commands at zero torque, at most `cycles` cycles.
void walk(Cia402Axis& axis, DriveStateMachine& drive, int cycles = 12) {
  for (int i = 0; i < cycles && !axis.enabled(); ++i) {
    axis.take(drive.feedback());
    drive.obey(axis.command(0.0).controlword);
    axis.take(drive.feedback());
  }
}

TEST(Cia402Axis, WalksTheDriveToOperationEnabledAtZeroTorqueThenCommandsTorque) {
  Cia402Axis axis(joint());
  DriveStateMachine drive;
  int cycles = 0;
  for (; cycles < 10 && !axis.enabled(); ++cycles) {
    axis.take(drive.feedback());
    const AxisCommand c = axis.command(30.0);
    if (!axis.enabled()) {
      EXPECT_EQ(c.target_torque_permille, 0);
    }
    drive.obey(c.controlword);
  }
  EXPECT_TRUE(axis.enabled());
  EXPECT_LE(cycles, 4);
  const AxisCommand c = axis.command(30.0);
  EXPECT_EQ(c.controlword, 0x000F);
  EXPECT_EQ(c.target_torque_permille, 667);
  EXPECT_FALSE(axis.failed());
}

TEST(Cia402Axis, AFaultBeforeTheFirstEnableIsResetByTheWalk) {
  Cia402Axis axis(joint());
  DriveStateMachine drive;
  drive.state = State::kFault;
  walk(axis, drive);
  EXPECT_TRUE(axis.enabled());
  EXPECT_FALSE(axis.failed());
}

TEST(Cia402Axis, LeavingOperationEnabledUnaskedIsAFailureThatHoldsUntilReset) {
  for (const State left_to : {State::kFault, State::kQuickStopActive, State::kSwitchOnDisabled}) {
    Cia402Axis axis(joint());
    DriveStateMachine drive;
    walk(axis, drive);
    ASSERT_TRUE(axis.enabled());
    drive.state = left_to;
    axis.take(drive.feedback());
    EXPECT_TRUE(axis.failed()) << cia402::to_string(left_to);
    // no torque, no walk back by itself: quick stop until someone resets
    for (int i = 0; i < 5; ++i) {
      const AxisCommand c = axis.command(30.0);
      EXPECT_EQ(c.controlword, 0x0002);
      EXPECT_EQ(c.target_torque_permille, 0);
      drive.obey(c.controlword);
      axis.take(drive.feedback());
    }
    axis.reset();
    walk(axis, drive);
    EXPECT_TRUE(axis.enabled()) << cia402::to_string(left_to);
  }
}

TEST(Cia402Axis, AQuickStopTheMasterAskedForHoldsAndResumesWithoutAFailure) {
  Cia402Axis axis(joint());
  DriveStateMachine drive;
  walk(axis, drive);
  ASSERT_TRUE(axis.enabled());
  drive.obey(axis.quick_stop().controlword);
  // the feedback of the cycle before still says enabled: the axis neither walks nor fails
  axis.take({cia402::statusword_for(State::kOperationEnabled), 0, 0});
  AxisCommand c = axis.command(9.0);
  EXPECT_EQ(c.controlword, 0x000F);  // resume at once: transition 16
  EXPECT_EQ(c.target_torque_permille, 200);
  // the drive showed the quick stop one SYNC late: still not a failure
  axis.take({cia402::statusword_for(State::kQuickStopActive), 0, 0});
  EXPECT_FALSE(axis.failed());
  EXPECT_TRUE(axis.holding());
  drive.obey(axis.command(9.0).controlword);
  EXPECT_EQ(drive.state, State::kOperationEnabled);
  axis.take(drive.feedback());
  EXPECT_FALSE(axis.holding());
  EXPECT_FALSE(axis.failed());
  // once the drive has reported enabled kResumeReports times in a row after the resume, a quick
  // stop the master did not ask for is one
  for (unsigned k = 1; k < Cia402Axis::kResumeReports; ++k) axis.take(drive.feedback());
  axis.take({cia402::statusword_for(State::kQuickStopActive), 0, 0});
  EXPECT_TRUE(axis.failed());
}

// Drives that answer late (a time-dilated emulator): after the quick stop and the resume went out,
// a report of enabled from before the quick stop took effect arrives, then the quick stop's own.
TEST(Cia402Axis, AQuickStopReportedBehindAnOlderEnabledIsStillTheOneAskedFor) {
  Cia402Axis axis(joint());
  DriveStateMachine drive;
  walk(axis, drive);
  (void)axis.quick_stop();
  (void)axis.command(1.0);
  axis.take({cia402::statusword_for(State::kOperationEnabled), 0, 0});  // sampled before the quick stop
  axis.take({cia402::statusword_for(State::kQuickStopActive), 0, 0});   // the quick stop, late
  EXPECT_FALSE(axis.failed());
  axis.take({cia402::statusword_for(State::kOperationEnabled), 0, 0});  // the resume
  axis.take({cia402::statusword_for(State::kFault), 0, 0});
  EXPECT_TRUE(axis.failed()) << "a fault is one at once";
}

TEST(Cia402Axis, RefusesAConfigurationThatIsNotPhysical) {
  auto with = [](auto change) {
    Cia402AxisConfig c = joint();
    change(c);
    return c;
  };
  EXPECT_THROW(Cia402Axis(with([](auto& c) { c.gear_ratio = 0; })), std::invalid_argument);
  EXPECT_THROW(Cia402Axis(with([](auto& c) { c.gear_efficiency = 1.2; })), std::invalid_argument);
  EXPECT_THROW(Cia402Axis(with([](auto& c) { c.encoder_ticks_per_rev = 0; })), std::invalid_argument);
  EXPECT_THROW(Cia402Axis(with([](auto& c) { c.rated_torque_nm = NAN; })), std::invalid_argument);
  EXPECT_THROW(Cia402Axis(with([](auto& c) { c.max_torque_nm = -1; })), std::invalid_argument);
}

}  // namespace
}  // namespace teleop::robot
