#pragma once
// What a master must know of teleop's emulated CiA 402 drive (teleop::drive, its defaults) to
// drive it as a joint: gear 100 at 80 %, 4096 ticks per motor turn, rated torque k_t x rated
// current = 0.01 N m x 1 A = 10 mN m; commands clamped at 1 N m at the joint.

#include "teleop/robot/cia402_axis.h"

namespace teleop::robot::test {

inline Cia402AxisConfig emulated_joint() {
  Cia402AxisConfig c;
  c.gear_ratio = 100.0;
  c.gear_efficiency = 0.8;
  c.encoder_ticks_per_rev = 4096.0;
  c.rated_torque_nm = 0.010;
  c.max_torque_nm = 1.0;
  return c;
}

}  // namespace teleop::robot::test
