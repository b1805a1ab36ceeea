#pragma once
// Per-motor unit conversion between what a drive speaks on the bus (encoder ticks, ticks/s,
// per mille of the rated current) and what the hand's samples carry (motor-side joint angle
// [rad] at the gearbox output, rad/s, A). Configuration is validated once (exceptions);
// conversions are real-time safe and reject NaN and values that do not fit the object.

#include <cstdint>

#include "teleop/can/can_frame.h"

namespace teleop::hand {

struct MotorChannelConfig {
  /// Encoder ticks per motor revolution (after quadrature decoding).
  double ticks_per_rev = 4096.0;
  /// Motor revolutions per revolution of the gearbox output.
  double gear_ratio = 1.0;
  /// +1: ticks count up with the joint angle; -1: they count down.
  int sign = 1;
  /// Joint angle [rad] at tick 0 (the drive's zero, e.g. where homing found the hard stop).
  double offset_rad = 0.0;
  /// Motor rated current [A] (object 0x6075): the unit of 0x6073 / 0x6078 (per mille).
  double rated_current_a = 1.0;
};

/// Converts one drive's units. q = sign * ticks * 2 pi / (ticks_per_rev * gear_ratio) + offset.
class MotorChannel {
 public:
  /// Throws std::invalid_argument for non-positive or non-finite scales, a sign other than
  /// +-1 or a non-finite offset.
  explicit MotorChannel(const MotorChannelConfig& config);

  const MotorChannelConfig& config() const { return config_; }
  /// Output angle of one tick [rad].
  double rad_per_tick() const { return rad_per_tick_; }

  /// Position actual value (0x6064) to joint angle [rad].
  double ticks_to_rad(int32_t ticks) const;
  /// Joint angle to target position (0x607A), rounded to the nearest tick; kValueOutOfRange for
  /// NaN/Inf or an angle beyond the INTEGER32 range.
  can::Result<int32_t> rad_to_ticks(double rad) const;
  /// Velocity actual value (0x606C) to rad/s.
  double ticks_per_s_to_radps(int32_t ticks_per_s) const;
  can::Result<int32_t> radps_to_ticks_per_s(double radps) const;
  /// Current actual value (0x6078, per mille of rated current) to A. Current is signed like
  /// the ticks: positive current drives the ticks up, so it is multiplied by `sign`.
  double permille_to_amps(int16_t permille) const;
  /// A current limit [A] (>= 0) to the max current object (0x6073, UNSIGNED16 per mille).
  can::Result<uint16_t> amps_to_max_current_permille(double amps) const;

 private:
  MotorChannelConfig config_;
  double rad_per_tick_ = 0.0;
};

}  // namespace teleop::hand
