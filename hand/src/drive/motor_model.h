#pragma once
// The drive's power stage and mechanics: a PWM bridge on a DC motor with a gearbox, driving a
// finger link between two hard stops, and the incremental encoder the drive sees it through.
// One substep at a time (the current loop's period); plain arithmetic, real-time safe.

#include <cstdint>

#include "teleop/hand/emulated_drive.h"

namespace teleop::hand::drive {

class MotorModel {
 public:
  /// `params` must outlive the model (the drive's configuration).
  MotorModel(const EmulatedMotorParams& params, double initial_position_rad, double substep_s);

  /// One substep with the bridge on at `volts` (an average PWM model: duty * supply).
  void energise(double volts);
  /// One substep with the bridge off: the current dies out through the free-wheeling diodes.
  void switch_off();
  /// One substep of the link; a jammed (stalled) link does not move.
  void move_link(bool stalled);

  double position_rad() const { return q_rad_; }
  double velocity_radps() const { return dq_radps_; }
  double current_a() const { return current_a_; }
  double supply_v() const { return params_.supply_v; }
  /// Encoder ticks per output radian (ticks_per_rev * gear_ratio / 2 pi).
  double ticks_per_rad() const { return ticks_per_rad_; }
  /// The encoder's count (saturated to INTEGER32) and the angle the drive measures from it.
  int32_t encoder_ticks() const;
  double measured_rad() const { return encoder_ticks() / ticks_per_rad_; }

 private:
  const EmulatedMotorParams& params_;
  double substep_s_;
  double ticks_per_rad_;
  double current_decay_;  // exp(-dt R / L): the winding's response over one substep
  double q_rad_;
  double dq_radps_ = 0.0;
  double current_a_ = 0.0;
  double voltage_v_ = 0.0;
};

/// Rounds to the nearest integer, saturated to the type's range (NaN: the minimum).
int32_t saturate_int32(double v);
int16_t saturate_int16(double v);

}  // namespace teleop::hand::drive
