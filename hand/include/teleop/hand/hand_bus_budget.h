#pragma once
// The hand's CAN bus budget: the frames one SYNC cycle of the hand puts on the bus and the load
// they make with the nodes' heartbeats, in the arithmetic of teleop/can/bus_load.h. See
// docs/can_bus_budget.md for the plan chosen.

#include <cstdint>

#include "teleop/can/bus_load.h"

namespace teleop::hand {

/// The hand's cyclic CANopen traffic: per cycle one SYNC, the motors' target positions packed
/// `motors_per_rpdo` to a frame (ceil(motors / motors_per_rpdo) RPDOs, the last one possibly
/// shorter), one TPDO of `tpdo_bytes` per motor; plus each node's heartbeat.
struct HandBusPlan {
  uint32_t motors = 9;
  double cycle_rate_hz = 250.0;
  double bitrate_bps = 1e6;
  bool sync = true;
  uint32_t sync_bytes = 0;            // 0, or 1 with the SYNC counter
  uint32_t rpdo_bytes_per_motor = 4;  // target position, INTEGER32
  uint32_t motors_per_rpdo = 2;       // one frame carries two motors' targets (dummy mapping)
  uint32_t tpdo_bytes = 8;            // position actual 4 + current actual 2 + statusword 2
  double heartbeat_hz = 10.0;         // per node; 0 = none
};

struct HandBusBudget {
  uint32_t frames_per_cycle = 0;
  uint32_t bits_per_cycle_nominal = 0;
  uint32_t bits_per_cycle_worst_case = 0;
  /// Time the cyclic frames occupy the bus per cycle, worst case [s].
  double cycle_bus_time_worst_case_s = 0.0;
  /// Cyclic frames plus heartbeats.
  can::BusLoad load;
  /// Highest cycle rate whose worst-case load (heartbeats included) stays at kBusLoadWarnFraction.
  double max_cycle_rate_hz = 0.0;
};

/// Throws std::invalid_argument for a plan that cannot be built (no motors, non-positive rate
/// or bitrate, more than 8 bytes in a frame, a SYNC with more than one byte).
HandBusBudget hand_bus_budget(const HandBusPlan& plan);

}  // namespace teleop::hand
