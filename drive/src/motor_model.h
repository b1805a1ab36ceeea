#pragma once
// The drive's power stage and motor: a PWM bridge on a DC motor's winding, the motor's torque
// through the gearbox onto the plant it turns (DrivePlant: the drive's own link, or a channel of
// a shared simulation), and the incremental encoder the drive sees the plant's output through.
// One substep at a time (the current loop's period); plain arithmetic, real-time safe.

#include <cstdint>

#include "teleop/drive/drive_plant.h"
#include "teleop/drive/emulated_drive.h"

namespace teleop::drive {

class MotorModel {
 public:
  /// `params` and `plant` must outlive the model (the drive's configuration and plant).
  MotorModel(const EmulatedMotorParams& params, DrivePlant& plant, double substep_s);

  /// One substep with the bridge on at `volts` (an average PWM model: duty * supply).
  void energise(double volts);
  /// One substep with the bridge off: the current dies out through the free-wheeling diodes.
  void switch_off();
  /// One substep of the plant under the motor's torque at the gearbox output,
  /// gear ratio x efficiency x k_t x current; a jammed (stalled) plant does not move.
  void turn(bool stalled);

  /// The plant's output angle [rad] and rate.
  double position_rad() const { return plant_.position_rad(); }
  double velocity_radps() const { return plant_.velocity_radps(); }
  double current_a() const { return current_a_; }
  double supply_v() const { return params_.supply_v; }
  /// Encoder ticks per output radian (ticks_per_rev * gear_ratio / 2 pi).
  double ticks_per_rad() const { return ticks_per_rad_; }
  /// The encoder's count (saturated to INTEGER32) and the angle the drive measures from it.
  int32_t encoder_ticks() const;
  double measured_rad() const { return encoder_ticks() / ticks_per_rad_; }

 private:
  const EmulatedMotorParams& params_;
  DrivePlant& plant_;
  double substep_s_;
  double ticks_per_rad_;
  double current_decay_;  // exp(-dt R / L): the winding's response over one substep
  double current_a_ = 0.0;
  double voltage_v_ = 0.0;
};

/// Rounds to the nearest integer, saturated to the type's range (NaN: the minimum).
int32_t saturate_int32(double v);
int16_t saturate_int16(double v);

}  // namespace teleop::drive
