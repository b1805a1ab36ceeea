// CiA 402: controlword commands, statusword decoding, every transition of the state machine,
// and the master helper walking a drive to operation enabled.
#include "teleop/can/cia402.h"

#include <gtest/gtest.h>

#include <array>

namespace teleop::can::cia402 {
namespace {

constexpr std::array<State, kStateCount> kStates = {
    State::kNotReadyToSwitchOn, State::kSwitchOnDisabled, State::kReadyToSwitchOn,     State::kSwitchedOn,
    State::kOperationEnabled,   State::kQuickStopActive,  State::kFaultReactionActive, State::kFault,
};
constexpr std::array<Command, kCommandCount> kCommands = {
    Command::kNone,
    Command::kShutdown,
    Command::kSwitchOn,
    Command::kEnableOperation,
    Command::kDisableOperation,
    Command::kDisableVoltage,
    Command::kQuickStop,
    Command::kFaultReset,
};

TEST(Cia402, ControlwordOfEveryCommand) {
  EXPECT_EQ(controlword_for(Command::kShutdown), 0x0006);
  EXPECT_EQ(controlword_for(Command::kSwitchOn), 0x0007);
  EXPECT_EQ(controlword_for(Command::kEnableOperation), 0x000F);
  EXPECT_EQ(controlword_for(Command::kDisableOperation), 0x0007);
  EXPECT_EQ(controlword_for(Command::kDisableVoltage), 0x0000);
  EXPECT_EQ(controlword_for(Command::kQuickStop), 0x0002);
  EXPECT_EQ(controlword_for(Command::kFaultReset), 0x0080);
}

TEST(Cia402, DecodesEveryCommandFromItsControlword) {
  for (Command c : kCommands) {
    if (c == Command::kNone) continue;
    const Command expected = c == Command::kDisableOperation ? Command::kSwitchOn : c;  // same bits
    EXPECT_EQ(command_from_controlword(controlword_for(c), 0x0000), expected) << to_string(c);
  }
  // bits outside the command pattern (halt, mode specific, manufacturer) do not matter
  EXPECT_EQ(command_from_controlword(0x010F, 0), Command::kEnableOperation);
  EXPECT_EQ(command_from_controlword(0xF006, 0), Command::kShutdown);
  // "don't care" bits of the patterns
  EXPECT_EQ(command_from_controlword(0x000D, 0), Command::kDisableVoltage);  // enable voltage 0
  EXPECT_EQ(command_from_controlword(0x000B, 0), Command::kQuickStop);       // quick stop 0
  EXPECT_EQ(command_from_controlword(0x000E, 0), Command::kShutdown);        // switch on 0
}

TEST(Cia402, FaultResetNeedsRisingEdgeOfBitSeven) {
  EXPECT_EQ(command_from_controlword(0x0080, 0x0000), Command::kFaultReset);
  EXPECT_EQ(command_from_controlword(0x008F, 0x000F), Command::kFaultReset);
  EXPECT_EQ(command_from_controlword(0x0080, 0x0080), Command::kNone);  // held high: nothing
  EXPECT_EQ(command_from_controlword(0x008F, 0x0080), Command::kNone);
}

TEST(Cia402, DecodesEveryStateFromStatusword) {
  for (State s : kStates) EXPECT_EQ(state_from_statusword(statusword_for(s)), s) << to_string(s);
  // as drives report them, with voltage enabled, remote, and mode bits
  EXPECT_EQ(state_from_statusword(0x0250), State::kSwitchOnDisabled);
  EXPECT_EQ(state_from_statusword(0x0231), State::kReadyToSwitchOn);
  EXPECT_EQ(state_from_statusword(0x0233), State::kSwitchedOn);
  EXPECT_EQ(state_from_statusword(0x1637), State::kOperationEnabled);
  EXPECT_EQ(state_from_statusword(0x0217), State::kQuickStopActive);
  EXPECT_EQ(state_from_statusword(0x021F), State::kFaultReactionActive);
  EXPECT_EQ(state_from_statusword(0x0218), State::kFault);
  EXPECT_EQ(state_from_statusword(0x0238), State::kFault);  // quick stop bit is "x" in fault
  EXPECT_EQ(state_from_statusword(0x0001), State::kUnknown);
  EXPECT_EQ(state_from_statusword(0x0025), State::kUnknown);
}

// The full table of command-driven transitions, from CiA 402's state diagram.
TEST(Cia402, TransitionsFromEveryStateForEveryCommand) {
  using S = State;
  // rows: kStates order; columns: kCommands order
  // (none, shutdown, switch on, enable op, disable op, disable voltage, quick stop, fault reset)
  // clang-format off
  const S expected[kStateCount][kCommandCount] = {
      // not ready to switch on: only the automatic transition 1 leaves it
      {S::kNotReadyToSwitchOn, S::kNotReadyToSwitchOn, S::kNotReadyToSwitchOn, S::kNotReadyToSwitchOn,
       S::kNotReadyToSwitchOn, S::kNotReadyToSwitchOn, S::kNotReadyToSwitchOn, S::kNotReadyToSwitchOn},
      // switch on disabled: 2
      {S::kSwitchOnDisabled, S::kReadyToSwitchOn, S::kSwitchOnDisabled, S::kSwitchOnDisabled, S::kSwitchOnDisabled,
       S::kSwitchOnDisabled, S::kSwitchOnDisabled, S::kSwitchOnDisabled},
      // ready to switch on: 3, 3+4, 7
      {S::kReadyToSwitchOn, S::kReadyToSwitchOn, S::kSwitchedOn, S::kOperationEnabled, S::kSwitchedOn,
       S::kSwitchOnDisabled, S::kSwitchOnDisabled, S::kReadyToSwitchOn},
      // switched on: 6, 4, 10
      {S::kSwitchedOn, S::kReadyToSwitchOn, S::kSwitchedOn, S::kOperationEnabled, S::kSwitchedOn,
       S::kSwitchOnDisabled, S::kSwitchOnDisabled, S::kSwitchedOn},
      // operation enabled: 8, 5, 9, 11
      {S::kOperationEnabled, S::kReadyToSwitchOn, S::kSwitchedOn, S::kOperationEnabled, S::kSwitchedOn,
       S::kSwitchOnDisabled, S::kQuickStopActive, S::kOperationEnabled},
      // quick stop active: 16, 12
      {S::kQuickStopActive, S::kQuickStopActive, S::kQuickStopActive, S::kOperationEnabled, S::kQuickStopActive,
       S::kSwitchOnDisabled, S::kQuickStopActive, S::kQuickStopActive},
      // fault reaction active: only the automatic transition 14 leaves it
      {S::kFaultReactionActive, S::kFaultReactionActive, S::kFaultReactionActive, S::kFaultReactionActive,
       S::kFaultReactionActive, S::kFaultReactionActive, S::kFaultReactionActive, S::kFaultReactionActive},
      // fault: 15
      {S::kFault, S::kFault, S::kFault, S::kFault, S::kFault, S::kFault, S::kFault, S::kSwitchOnDisabled},
  };  // clang-format on

  for (int s = 0; s < kStateCount; ++s) {
    for (int c = 0; c < kCommandCount; ++c) {
      EXPECT_EQ(next_state(kStates[s], kCommands[c]), expected[s][c])
          << "from " << to_string(kStates[s]) << " on " << to_string(kCommands[c]);
      // and the same through the controlword a master would send
      if (kCommands[c] != Command::kNone) {
        const Command decoded = command_from_controlword(controlword_for(kCommands[c]), 0x0000);
        EXPECT_EQ(next_state(kStates[s], decoded), expected[s][c]);
      }
    }
  }
}

// A drive as the pure state machine: what the master helper sees and drives.
struct PureDrive {
  State state;
  uint16_t controlword = 0;
  void apply(uint16_t cw) {
    state = next_state(state, command_from_controlword(cw, controlword));
    controlword = cw;
  }
};

int walk_to_enabled(State start, int max_cycles = 10) {
  PureDrive drive{start};
  uint16_t cw = 0;
  for (int i = 1; i <= max_cycles; ++i) {
    cw = next_controlword(statusword_for(drive.state), cw);
    drive.apply(cw);
    if (drive.state == State::kOperationEnabled) return i;
  }
  return -1;
}

TEST(Cia402, MasterHelperReachesOperationEnabledFromSwitchOnDisabled) {
  PureDrive drive{State::kSwitchOnDisabled};
  uint16_t cw = 0;
  const uint16_t expected_cw[] = {0x0006, 0x0007, 0x000F};
  const State expected_state[] = {State::kReadyToSwitchOn, State::kSwitchedOn, State::kOperationEnabled};
  for (int i = 0; i < 3; ++i) {
    cw = next_controlword(statusword_for(drive.state), cw);
    EXPECT_EQ(cw, expected_cw[i]);
    drive.apply(cw);
    EXPECT_EQ(drive.state, expected_state[i]);
  }
  // and then holds it
  EXPECT_EQ(next_controlword(statusword_for(drive.state), cw), 0x000F);
}

TEST(Cia402, MasterHelperRecoversFromFaultWithFaultReset) {
  PureDrive drive{State::kFault};
  uint16_t cw = 0x000F;  // what the master sent when the fault happened
  cw = next_controlword(statusword_for(drive.state), cw);
  EXPECT_EQ(cw, 0x0080);  // rising edge of bit 7
  drive.apply(cw);
  EXPECT_EQ(drive.state, State::kSwitchOnDisabled);
  EXPECT_EQ(walk_to_enabled(State::kFault), 4);  // reset, shutdown, switch on, enable
}

TEST(Cia402, MasterHelperRetriesFaultResetWithFreshEdges) {
  // a drive whose fault persists: the helper must keep producing rising edges
  uint16_t cw = 0;
  int edges = 0;
  for (int i = 0; i < 6; ++i) {
    const uint16_t next = next_controlword(statusword_for(State::kFault), cw);
    if (command_from_controlword(next, cw) == Command::kFaultReset) ++edges;
    cw = next;
  }
  EXPECT_EQ(edges, 3);
}

TEST(Cia402, MasterHelperReachesOperationEnabledFromEveryReachableState) {
  EXPECT_EQ(walk_to_enabled(State::kSwitchOnDisabled), 3);
  EXPECT_EQ(walk_to_enabled(State::kReadyToSwitchOn), 2);
  EXPECT_EQ(walk_to_enabled(State::kSwitchedOn), 1);
  EXPECT_EQ(walk_to_enabled(State::kOperationEnabled), 1);
  EXPECT_EQ(walk_to_enabled(State::kQuickStopActive), 4);  // through switch on disabled
  EXPECT_EQ(walk_to_enabled(State::kFault), 4);
  // states only the drive itself leaves: the helper waits with 0x0000
  EXPECT_EQ(walk_to_enabled(State::kNotReadyToSwitchOn), -1);
  EXPECT_EQ(walk_to_enabled(State::kFaultReactionActive), -1);
  EXPECT_EQ(next_controlword(statusword_for(State::kFaultReactionActive), 0x000F), 0x0000);
  EXPECT_EQ(next_controlword(0x0001, 0x000F), 0x0000);  // unknown statusword: disable
}

}  // namespace
}  // namespace teleop::can::cia402
