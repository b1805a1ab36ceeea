#include "motor_model.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace teleop::drive {

int32_t saturate_int32(double v) {
  if (!(v > static_cast<double>(std::numeric_limits<int32_t>::min()))) return std::numeric_limits<int32_t>::min();
  if (!(v < static_cast<double>(std::numeric_limits<int32_t>::max()))) return std::numeric_limits<int32_t>::max();
  return static_cast<int32_t>(std::lround(v));
}

int16_t saturate_int16(double v) {
  if (!(v > -32768.0)) return -32768;
  if (!(v < 32767.0)) return 32767;
  return static_cast<int16_t>(std::lround(v));
}

MotorModel::MotorModel(const EmulatedMotorParams& params, DrivePlant& plant, double substep_s)
    : params_(params),
      plant_(plant),
      substep_s_(substep_s),
      ticks_per_rad_(params.encoder_ticks_per_rev * params.gear_ratio / (2.0 * M_PI)),
      current_decay_(std::exp(-substep_s * params.resistance_ohm / params.inductance_h)) {}

int32_t MotorModel::encoder_ticks() const { return saturate_int32(plant_.position_rad() * ticks_per_rad_); }

void MotorModel::energise(double volts) {
  const EmulatedMotorParams& m = params_;
  const double omega_motor = plant_.velocity_radps() * m.gear_ratio;
  const double duty = volts / m.supply_v;
  voltage_v_ = duty * m.supply_v;
  // winding: L di/dt = V - R i - k omega, exact for V and omega constant over the substep
  const double steady = (voltage_v_ - m.torque_constant_nm_per_a * omega_motor) / m.resistance_ohm;
  current_a_ = steady + (current_a_ - steady) * current_decay_;
}

void MotorModel::switch_off() {
  voltage_v_ = 0;
  current_a_ = 0;
}

void MotorModel::turn(bool stalled) {
  const EmulatedMotorParams& m = params_;
  plant_.apply(m.gear_ratio * m.gear_efficiency * m.torque_constant_nm_per_a * current_a_, substep_s_, stalled);
}

}  // namespace teleop::drive
