#include "teleop/hand/hand_bus_budget.h"

#include <stdexcept>

namespace teleop::hand {

using can::bus_load;
using can::CanIdFormat;
using can::frame_bits_nominal;
using can::frame_bits_worst_case;
using can::kBusLoadWarnFraction;
using can::Traffic;

HandBusBudget hand_bus_budget(const HandBusPlan& plan) {
  if (plan.motors == 0) throw std::invalid_argument("hand bus plan: no motors");
  if (!(plan.cycle_rate_hz > 0)) throw std::invalid_argument("hand bus plan: cycle_rate_hz must be > 0");
  if (!(plan.bitrate_bps > 0)) throw std::invalid_argument("hand bus plan: bitrate_bps must be > 0");
  if (plan.heartbeat_hz < 0) throw std::invalid_argument("hand bus plan: heartbeat_hz must be >= 0");
  if (plan.sync_bytes > 1) throw std::invalid_argument("hand bus plan: a SYNC carries at most the counter byte");
  if (plan.motors_per_rpdo == 0 || plan.rpdo_bytes_per_motor == 0 ||
      plan.motors_per_rpdo * plan.rpdo_bytes_per_motor > 8) {
    throw std::invalid_argument("hand bus plan: motors_per_rpdo * rpdo_bytes_per_motor must be 1..8 bytes");
  }
  if (plan.tpdo_bytes == 0 || plan.tpdo_bytes > 8) throw std::invalid_argument("hand bus plan: tpdo_bytes 1..8");

  // the cycle: SYNC, full RPDOs, one shorter RPDO for the remainder, TPDOs
  const uint32_t full_rpdos = plan.motors / plan.motors_per_rpdo;
  const uint32_t rest = plan.motors % plan.motors_per_rpdo;
  const Traffic cyclic[] = {
      {plan.sync ? 1u : 0u, plan.sync_bytes, plan.cycle_rate_hz, CanIdFormat::kStandard},
      {full_rpdos, plan.motors_per_rpdo * plan.rpdo_bytes_per_motor, plan.cycle_rate_hz, CanIdFormat::kStandard},
      {rest > 0 ? 1u : 0u, rest * plan.rpdo_bytes_per_motor, plan.cycle_rate_hz, CanIdFormat::kStandard},
      {plan.motors, plan.tpdo_bytes, plan.cycle_rate_hz, CanIdFormat::kStandard},
  };
  HandBusBudget budget;
  for (const Traffic& t : cyclic) {
    budget.frames_per_cycle += t.frames;
    budget.bits_per_cycle_nominal += t.frames * frame_bits_nominal(t.data_bytes, t.format);
    budget.bits_per_cycle_worst_case += t.frames * frame_bits_worst_case(t.data_bytes, t.format);
  }
  budget.cycle_bus_time_worst_case_s = budget.bits_per_cycle_worst_case / plan.bitrate_bps;

  const Traffic all[] = {
      cyclic[0], cyclic[1], cyclic[2], cyclic[3], {plan.motors, 1, plan.heartbeat_hz, CanIdFormat::kStandard}};
  budget.load = bus_load(all, plan.bitrate_bps);

  const double heartbeat_bits_per_s = plan.motors * plan.heartbeat_hz * frame_bits_worst_case(1);
  const double available = kBusLoadWarnFraction * plan.bitrate_bps - heartbeat_bits_per_s;
  budget.max_cycle_rate_hz = available > 0 ? available / budget.bits_per_cycle_worst_case : 0.0;
  return budget;
}

}  // namespace teleop::hand
