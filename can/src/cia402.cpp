#include "teleop/can/cia402.h"

namespace teleop::can::cia402 {

uint16_t controlword_for(Command command) {
  switch (command) {
    case Command::kNone:
      return 0x0000;
    case Command::kShutdown:
      return cw::kEnableVoltage | cw::kQuickStop;  // 0x06
    case Command::kSwitchOn:
    case Command::kDisableOperation:
      return cw::kSwitchOn | cw::kEnableVoltage | cw::kQuickStop;  // 0x07
    case Command::kEnableOperation:
      return cw::kSwitchOn | cw::kEnableVoltage | cw::kQuickStop | cw::kEnableOperation;  // 0x0F
    case Command::kDisableVoltage:
      return 0x0000;
    case Command::kQuickStop:
      return cw::kEnableVoltage;  // 0x02
    case Command::kFaultReset:
      return cw::kFaultReset;  // 0x80
  }
  return 0x0000;
}

Command command_from_controlword(uint16_t controlword, uint16_t previous_controlword) {
  if (controlword & cw::kFaultReset) {
    return (previous_controlword & cw::kFaultReset) ? Command::kNone : Command::kFaultReset;
  }
  // bit patterns of CiA 402, most significant condition first
  if ((controlword & 0x0082) == 0x0000) return Command::kDisableVoltage;
  if ((controlword & 0x0086) == 0x0002) return Command::kQuickStop;
  if ((controlword & 0x0087) == 0x0006) return Command::kShutdown;
  if ((controlword & 0x008F) == 0x0007) return Command::kSwitchOn;
  if ((controlword & 0x008F) == 0x000F) return Command::kEnableOperation;
  return Command::kNone;
}

State state_from_statusword(uint16_t statusword) {
  switch (statusword & 0x004F) {
    case 0x0000:
      return State::kNotReadyToSwitchOn;
    case 0x0040:
      return State::kSwitchOnDisabled;
    case 0x000F:
      return State::kFaultReactionActive;
    case 0x0008:
      return State::kFault;
    default:
      break;
  }
  switch (statusword & 0x006F) {
    case 0x0021:
      return State::kReadyToSwitchOn;
    case 0x0023:
      return State::kSwitchedOn;
    case 0x0027:
      return State::kOperationEnabled;
    case 0x0007:
      return State::kQuickStopActive;
    default:
      break;
  }
  return State::kUnknown;
}

uint16_t statusword_for(State state) {
  switch (state) {
    case State::kNotReadyToSwitchOn:
      return 0x0000;
    case State::kSwitchOnDisabled:
      return sw::kSwitchOnDisabled;
    case State::kReadyToSwitchOn:
      return sw::kQuickStop | sw::kReadyToSwitchOn;
    case State::kSwitchedOn:
      return sw::kQuickStop | sw::kSwitchedOn | sw::kReadyToSwitchOn;
    case State::kOperationEnabled:
      return sw::kQuickStop | sw::kOperationEnabled | sw::kSwitchedOn | sw::kReadyToSwitchOn;
    case State::kQuickStopActive:
      return sw::kOperationEnabled | sw::kSwitchedOn | sw::kReadyToSwitchOn;
    case State::kFaultReactionActive:
      return sw::kFault | sw::kOperationEnabled | sw::kSwitchedOn | sw::kReadyToSwitchOn;
    case State::kFault:
      return sw::kFault;
    case State::kUnknown:
      break;
  }
  return 0x0000;
}

State next_state(State state, Command command) {
  switch (state) {
    case State::kSwitchOnDisabled:
      if (command == Command::kShutdown) return State::kReadyToSwitchOn;  // 2
      break;
    case State::kReadyToSwitchOn:
      switch (command) {
        case Command::kSwitchOn:
        case Command::kDisableOperation:
          return State::kSwitchedOn;  // 3
        case Command::kEnableOperation:
          return State::kOperationEnabled;  // 3 + 4
        case Command::kDisableVoltage:
        case Command::kQuickStop:
          return State::kSwitchOnDisabled;  // 7
        default:
          break;
      }
      break;
    case State::kSwitchedOn:
      switch (command) {
        case Command::kEnableOperation:
          return State::kOperationEnabled;  // 4
        case Command::kShutdown:
          return State::kReadyToSwitchOn;  // 6
        case Command::kDisableVoltage:
        case Command::kQuickStop:
          return State::kSwitchOnDisabled;  // 10
        default:
          break;
      }
      break;
    case State::kOperationEnabled:
      switch (command) {
        case Command::kSwitchOn:
        case Command::kDisableOperation:
          return State::kSwitchedOn;  // 5
        case Command::kShutdown:
          return State::kReadyToSwitchOn;  // 8
        case Command::kDisableVoltage:
          return State::kSwitchOnDisabled;  // 9
        case Command::kQuickStop:
          return State::kQuickStopActive;  // 11
        default:
          break;
      }
      break;
    case State::kQuickStopActive:
      switch (command) {
        case Command::kDisableVoltage:
          return State::kSwitchOnDisabled;  // 12
        case Command::kEnableOperation:
          return State::kOperationEnabled;  // 16
        default:
          break;
      }
      break;
    case State::kFault:
      if (command == Command::kFaultReset) return State::kSwitchOnDisabled;  // 15
      break;
    case State::kNotReadyToSwitchOn:
    case State::kFaultReactionActive:
    case State::kUnknown:
      break;
  }
  return state;
}

uint16_t next_controlword(uint16_t statusword, uint16_t previous_controlword) {
  switch (state_from_statusword(statusword)) {
    case State::kSwitchOnDisabled:
      return controlword_for(Command::kShutdown);
    case State::kReadyToSwitchOn:
      return controlword_for(Command::kSwitchOn);
    case State::kSwitchedOn:
    case State::kOperationEnabled:
      return controlword_for(Command::kEnableOperation);
    case State::kFault:
      // a reset is a rising edge of bit 7: drop the bit after each attempt
      return (previous_controlword & cw::kFaultReset) ? controlword_for(Command::kDisableVoltage)
                                                      : controlword_for(Command::kFaultReset);
    case State::kQuickStopActive:
    case State::kNotReadyToSwitchOn:
    case State::kFaultReactionActive:
    case State::kUnknown:
      break;
  }
  return controlword_for(Command::kDisableVoltage);
}

const char* to_string(State state) {
  switch (state) {
    case State::kNotReadyToSwitchOn:
      return "not ready to switch on";
    case State::kSwitchOnDisabled:
      return "switch on disabled";
    case State::kReadyToSwitchOn:
      return "ready to switch on";
    case State::kSwitchedOn:
      return "switched on";
    case State::kOperationEnabled:
      return "operation enabled";
    case State::kQuickStopActive:
      return "quick stop active";
    case State::kFaultReactionActive:
      return "fault reaction active";
    case State::kFault:
      return "fault";
    case State::kUnknown:
      break;
  }
  return "unknown";
}

const char* to_string(Command command) {
  switch (command) {
    case Command::kNone:
      return "none";
    case Command::kShutdown:
      return "shutdown";
    case Command::kSwitchOn:
      return "switch on";
    case Command::kEnableOperation:
      return "enable operation";
    case Command::kDisableOperation:
      return "disable operation";
    case Command::kDisableVoltage:
      return "disable voltage";
    case Command::kQuickStop:
      return "quick stop";
    case Command::kFaultReset:
      return "fault reset";
  }
  return "unknown";
}

}  // namespace teleop::can::cia402
