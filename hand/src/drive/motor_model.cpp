#include "motor_model.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace teleop::hand::drive {

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

MotorModel::MotorModel(const EmulatedMotorParams& params, double initial_position_rad, double substep_s)
    : params_(params),
      substep_s_(substep_s),
      ticks_per_rad_(params.encoder_ticks_per_rev * params.gear_ratio / (2.0 * M_PI)),
      current_decay_(std::exp(-substep_s * params.resistance_ohm / params.inductance_h)),
      q_rad_(initial_position_rad) {}

int32_t MotorModel::encoder_ticks() const { return saturate_int32(q_rad_ * ticks_per_rad_); }

void MotorModel::energise(double volts) {
  const EmulatedMotorParams& m = params_;
  const double omega_motor = dq_radps_ * m.gear_ratio;
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

void MotorModel::move_link(bool stalled) {
  const EmulatedMotorParams& m = params_;
  if (stalled) {
    dq_radps_ = 0;
    return;
  }
  // J ddq = N eta k i - b dq + hard stops (a penalty spring-damper that only pushes)
  double torque =
      m.gear_ratio * m.gear_efficiency * m.torque_constant_nm_per_a * current_a_ - m.viscous_nms_per_rad * dq_radps_;
  if (q_rad_ > m.stop_max_rad) {
    torque += std::min(
        0.0, -m.stop_stiffness_nm_per_rad * (q_rad_ - m.stop_max_rad) - m.stop_damping_nms_per_rad * dq_radps_);
  } else if (q_rad_ < m.stop_min_rad) {
    torque += std::max(
        0.0, -m.stop_stiffness_nm_per_rad * (q_rad_ - m.stop_min_rad) - m.stop_damping_nms_per_rad * dq_radps_);
  }
  // the rotor's inertia appears at the output multiplied by the square of the gear ratio
  const double inertia = m.link_inertia_kgm2 + m.rotor_inertia_kgm2 * m.gear_ratio * m.gear_ratio;
  dq_radps_ += torque / inertia * substep_s_;
  q_rad_ += dq_radps_ * substep_s_;
}

}  // namespace teleop::hand::drive
