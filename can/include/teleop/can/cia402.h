#pragma once
// CiA 402 (drives and motion control): the objects of a position or torque drive, the controlword commands,
// the statusword state coding, the device state machine (PDS FSA) as a pure function, and a
// master-side helper that walks a drive to "operation enabled" one controlword at a time.
// Everything here is constexpr-friendly plain code: real-time safe.

#include <cstdint>

namespace teleop::can::cia402 {

/// Object indices (subindex 0 unless noted).
namespace od {
constexpr uint16_t kAbortConnectionOptionCode = 0x6007;  // INTEGER16: the reaction to a lost master
constexpr uint16_t kErrorCode = 0x603F;                // UNSIGNED16, last EMCY error code
constexpr uint16_t kControlword = 0x6040;              // UNSIGNED16, rw, RPDO
constexpr uint16_t kStatusword = 0x6041;               // UNSIGNED16, ro, TPDO
constexpr uint16_t kModesOfOperation = 0x6060;         // INTEGER8, rw
constexpr uint16_t kModesOfOperationDisplay = 0x6061;  // INTEGER8, ro
constexpr uint16_t kPositionActualValue = 0x6064;      // INTEGER32 [ticks], ro, TPDO
constexpr uint16_t kFollowingErrorWindow = 0x6065;     // UNSIGNED32 [ticks], 0xFFFFFFFF = off
constexpr uint16_t kFollowingErrorTimeout = 0x6066;    // UNSIGNED16 [ms]
constexpr uint16_t kVelocityActualValue = 0x606C;      // INTEGER32 [ticks/s], ro, TPDO
constexpr uint16_t kTargetTorque = 0x6071;             // INTEGER16 [per mille of rated torque], rw, RPDO
constexpr uint16_t kMaxCurrent = 0x6073;               // UNSIGNED16 [per mille of rated current]
constexpr uint16_t kMotorRatedCurrent = 0x6075;        // UNSIGNED32 [mA]
constexpr uint16_t kMotorRatedTorque = 0x6076;         // UNSIGNED32 [mN m], the unit of 0x6071 / 0x6077
constexpr uint16_t kTorqueActualValue = 0x6077;        // INTEGER16 [per mille of rated torque], TPDO
constexpr uint16_t kCurrentActualValue = 0x6078;       // INTEGER16 [per mille of rated current], TPDO
constexpr uint16_t kTargetPosition = 0x607A;           // INTEGER32 [ticks], rw, RPDO
constexpr uint16_t kQuickStopOptionCode = 0x605A;      // INTEGER16: how quick stop brakes, where it ends
constexpr uint16_t kSoftwarePositionLimit = 0x607D;    // sub 1 min, sub 2 max: INTEGER32 [ticks]
}  // namespace od

/// Modes of operation (0x6060 / 0x6061).
constexpr int8_t kModeNone = 0;
constexpr int8_t kModeCyclicSynchronousPosition = 8;
constexpr int8_t kModeCyclicSynchronousTorque = 10;

/// Quick stop option code (0x605A) 6: brake on the quick stop ramp and stay in quick stop active,
/// from where enable operation resumes (transition 16) without passing through power off.
constexpr int16_t kQuickStopRampAndHold = 6;

/// Abort connection option codes (0x6007): what the drive does when it loses its master (a
/// heartbeat it consumes times out). 4 and up, and negative codes, are the manufacturer's.
namespace abort_connection {
constexpr int16_t kNoAction = 0;
constexpr int16_t kFault = 1;           // fault signal: EMCY, fault reaction, fault
constexpr int16_t kDisableVoltage = 2;  // power off at once (transition 9/10/12)
constexpr int16_t kQuickStop = 3;       // quick stop (transition 11): brake and hold
}  // namespace abort_connection

/// Controlword bits (0x6040).
namespace cw {
constexpr uint16_t kSwitchOn = 1u << 0;
constexpr uint16_t kEnableVoltage = 1u << 1;
constexpr uint16_t kQuickStop = 1u << 2;  // active low: 0 requests a quick stop
constexpr uint16_t kEnableOperation = 1u << 3;
constexpr uint16_t kFaultReset = 1u << 7;  // acts on the rising edge
constexpr uint16_t kHalt = 1u << 8;
}  // namespace cw

/// Statusword bits (0x6041).
namespace sw {
constexpr uint16_t kReadyToSwitchOn = 1u << 0;
constexpr uint16_t kSwitchedOn = 1u << 1;
constexpr uint16_t kOperationEnabled = 1u << 2;
constexpr uint16_t kFault = 1u << 3;
constexpr uint16_t kVoltageEnabled = 1u << 4;
constexpr uint16_t kQuickStop = 1u << 5;  // active low: 0 while a quick stop is active
constexpr uint16_t kSwitchOnDisabled = 1u << 6;
constexpr uint16_t kWarning = 1u << 7;
constexpr uint16_t kRemote = 1u << 9;
constexpr uint16_t kTargetReached = 1u << 10;
constexpr uint16_t kInternalLimitActive = 1u << 11;
constexpr uint16_t kDriveFollowsCommand = 1u << 12;  // cyclic synchronous modes
constexpr uint16_t kFollowingError = 1u << 13;       // position modes
}  // namespace sw

/// States of the power drive system finite state automaton.
enum class State : uint8_t {
  kNotReadyToSwitchOn,
  kSwitchOnDisabled,
  kReadyToSwitchOn,
  kSwitchedOn,
  kOperationEnabled,
  kQuickStopActive,
  kFaultReactionActive,
  kFault,
  kUnknown,  // a statusword matching no state pattern
};
constexpr int kStateCount = 8;  // without kUnknown

/// Device control commands, coded in controlword bits 0..3 and 7.
enum class Command : uint8_t {
  kNone,              // no valid command (e.g. fault reset bit held high)
  kShutdown,          // 0x06: transitions 2, 6, 8 -> ready to switch on
  kSwitchOn,          // 0x07: transition 3 -> switched on
  kEnableOperation,   // 0x0F: transition 4 (and 3+4 from ready to switch on, 16 from quick stop)
  kDisableOperation,  // 0x07: transition 5; the same bits as kSwitchOn
  kDisableVoltage,    // 0x00: transitions 7, 9, 10, 12 -> switch on disabled
  kQuickStop,         // 0x02: transition 11 (and 7, 10) -> quick stop active
  kFaultReset,        // 0x80 rising edge: transition 15 -> switch on disabled
};
constexpr int kCommandCount = 8;  // with kNone

/// The controlword that issues a command (kNone: 0x0000 with no meaning).
uint16_t controlword_for(Command command);
/// The command a drive reads from a controlword. Fault reset needs the rising edge of bit 7
/// (previous value without it); while bit 7 stays high no other command is recognised.
Command command_from_controlword(uint16_t controlword, uint16_t previous_controlword);

/// Decodes the state bits of a statusword (masks 0x4F / 0x6F of CiA 402).
State state_from_statusword(uint16_t statusword);
/// The state bits a drive reports in a state (bit 5 "quick stop" set except while it is active).
uint16_t statusword_for(State state);

/// The state a drive moves to when it reads `command` in `state`: the command-driven
/// transitions 2..12, 15 and 16 (16: quick stop option codes 5..8, which keep the drive in
/// quick stop active until enabled again or disabled). Automatic transitions (0, 1, 13, 14)
/// are the drive's own business; commands that are not valid in a state leave it unchanged.
State next_state(State state, Command command);

/// Master side: the controlword to send next, given the drive's statusword and the controlword
/// sent before, to walk the drive to operation enabled. From fault it alternates 0x0000 and
/// 0x0080 (each rising edge is one reset attempt); from quick stop active it disables voltage
/// first (a clean restart through switch on disabled); in not ready to switch on and fault
/// reaction active it waits (0x0000). Once enabled it keeps sending enable operation.
uint16_t next_controlword(uint16_t statusword, uint16_t previous_controlword);

const char* to_string(State state);
const char* to_string(Command command);

}  // namespace teleop::can::cia402
