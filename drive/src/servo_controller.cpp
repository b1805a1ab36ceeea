#include "servo_controller.h"

#include <algorithm>
#include <cmath>

namespace teleop::drive {

ServoController::ServoController(const EmulatedControllerParams& gains, double supply_v, double measured_rad)
    : gains_(gains),
      supply_v_(supply_v),
      velocity_filter_alpha_(
          1.0 - std::exp(-2.0 * M_PI * gains.velocity_filter_hz * (gains.substep_s * gains.position_loop_divider))),
      measured_prev_rad_(measured_rad) {}

void ServoController::sense(double measured_rad) {
  const double v_raw = (measured_rad - measured_prev_rad_) / position_period_s();
  measured_prev_rad_ = measured_rad;
  velocity_filtered_radps_ += velocity_filter_alpha_ * (v_raw - velocity_filtered_radps_);
}

void ServoController::follow(double measured_rad) {
  position_.ref_rad = measured_rad;
  position_.ref_velocity_radps = 0;
  current_.ref_a = 0;
}

void ServoController::approach(double target_rad) {
  const double period_s = position_period_s();
  const double max_step = gains_.max_reference_velocity_radps * period_s;
  const double step = std::clamp(target_rad - position_.ref_rad, -max_step, max_step);
  position_.ref_rad += step;
  position_.ref_velocity_radps = step / period_s;
}

void ServoController::hold() { position_.ref_velocity_radps = 0; }

ServoController::Regulation ServoController::regulate(double measured_rad, double current_limit_a) {
  const EmulatedControllerParams& c = gains_;
  // PID with derivative on the error (the reference is rate-limited, so there is no kick)
  const double error = position_.ref_rad - measured_rad;
  const double derror = position_.ref_velocity_radps - velocity_filtered_radps_;
  const double unsaturated =
      c.position_kp_a_per_rad * error + position_.integral_a + c.position_kd_a_s_per_rad * derror;
  const double command = std::clamp(unsaturated, -current_limit_a, current_limit_a);
  // anti-windup: integrate unless saturated and the error would push further into saturation
  if (command == unsaturated || (error > 0) != (unsaturated > 0)) {
    const double integral_limit = std::min(c.position_integral_limit_a, current_limit_a);
    position_.integral_a = std::clamp(position_.integral_a + c.position_ki_a_per_rad_s * error * position_period_s(),
                                      -integral_limit, integral_limit);
  }
  current_.ref_a = command;
  return {error, command != unsaturated};
}

bool ServoController::drive_current(double current_a, double current_limit_a, double measured_rad) {
  hold_at(measured_rad);
  position_.integral_a = 0;
  current_.ref_a = std::clamp(current_a, -current_limit_a, current_limit_a);
  return current_.ref_a != current_a;
}

double ServoController::current_loop(double current_a) {
  const EmulatedControllerParams& c = gains_;
  const double error = current_.ref_a - current_a;
  const double unsaturated = c.current_kp_v_per_a * error + current_.integral_v;
  const double volts = std::clamp(unsaturated, -supply_v_, supply_v_);
  if (volts == unsaturated || (error > 0) != (unsaturated > 0)) {
    current_.integral_v =
        std::clamp(current_.integral_v + c.current_ki_v_per_a_s * error * c.substep_s, -supply_v_, supply_v_);
  }
  return volts;
}

void ServoController::hold_at(double measured_rad) {
  position_.ref_rad = measured_rad;
  position_.ref_velocity_radps = 0;
}

void ServoController::start_at(double measured_rad) {
  hold_at(measured_rad);
  position_.integral_a = 0;
  current_.integral_v = 0;
}

void ServoController::release() {
  current_.ref_a = 0;
  position_.integral_a = 0;
  current_.integral_v = 0;
}

void ServoController::reset(double measured_rad) {
  hold_at(measured_rad);
  release();
}

}  // namespace teleop::drive
