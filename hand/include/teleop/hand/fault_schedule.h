#pragma once
// Faults an emulated hand is told to inject at given times, e.g. from teleop_hand_emulator's
// command line: "--inject 2.5:4:emcy:0x2310" raises an over-current fault in node 4 2.5 s after
// start. Parsing validates once (exceptions); applying is real-time safe.
//
// Spec: SECONDS:NODE:KIND[:VALUE] with KIND one of
//   heartbeat-stop, heartbeat-resume     the node's heartbeat (consumer timeout at the master)
//   emcy:CODE                            a drive fault with this EMCY code (hex 0x.. or decimal)
//   stall, free                          jam / free the motor (a stall ends in a following error)
//   drop-tpdo[:COUNT], tpdo-resume       drop the next COUNT TPDOs (default: until resumed)
//   drop-rpdo[:COUNT], rpdo-resume       drop the next COUNT RPDOs
//   refuse-sdo, accept-sdo               abort every SDO request (0x08000021)
//   bus-off, restarted                   an error frame as a controller reports it (node ignored
//                                        but must be one of the emulated nodes: it sends it)

#include <cstdint>
#include <string>

#include "teleop/can/can_bus.h"
#include "teleop/can/cia301.h"
#include "teleop/drive/emulated_drive.h"

namespace teleop::hand {

enum class FaultKind : uint8_t {
  kHeartbeatStop,
  kHeartbeatResume,
  kEmcy,
  kStall,
  kFree,
  kDropTpdo,
  kTpdoResume,
  kDropRpdo,
  kRpdoResume,
  kRefuseSdo,
  kAcceptSdo,
  kBusOff,
  kRestarted,
};

/// The spec's name of a kind ("heartbeat-stop", ...).
const char* to_string(FaultKind kind);

struct ScheduledFault {
  double at_s = 0.0;
  can::NodeId node = 1;
  FaultKind kind = FaultKind::kHeartbeatStop;
  uint32_t value = 0;  // EMCY code, or a PDO count (drive::EmulatedDrive::kDropForever)
};

/// Parses SECONDS:NODE:KIND[:VALUE]. Throws std::invalid_argument naming the spec and the problem.
ScheduledFault parse_fault_spec(const std::string& spec);

/// Does it: on the drive, or for bus-off / restarted an error frame sent on `bus`.
can::CanStatus apply_fault(const ScheduledFault& fault, drive::EmulatedDrive& drive, can::CanBus& bus);

}  // namespace teleop::hand
