#include "operator_motion.h"

#include <algorithm>
#include <cmath>

namespace teleop::leader {
namespace {

// smoothstep over [0, ramp]: value and rate; 1 and 0 after it (no step at either end)
struct Ramp {
  double value;
  double rate;
};
Ramp smoothstep(double t_s, double ramp_s) {
  if (ramp_s <= 0 || t_s >= ramp_s) return {1.0, 0.0};
  const double x = std::max(0.0, t_s / ramp_s);
  return {x * x * (3 - 2 * x), 6 * x * (1 - x) / ramp_s};
}

}  // namespace

void OperatorMotion::sample(double t_s, JointVector& q_rad, JointVector& dq_radps) const {
  if (config_.kind == OperatorMotionConfig::Kind::kPushHold) {
    push_hold(t_s, q_rad, dq_radps);
  } else if (config_.kind == OperatorMotionConfig::Kind::kRecorded) {
    config_.recording->sample(t_s, q_rad, dq_radps);
  } else {
    sine(t_s, q_rad, dq_radps);
  }
}

void OperatorMotion::intended_torque(double t_s, JointVector& tau_nm) const {
  if (config_.kind == OperatorMotionConfig::Kind::kRecorded) {
    config_.recording->sample_torque(t_s, tau_nm);
  } else {
    std::fill_n(tau_nm.begin(), config_.joints, 0.0);
  }
}

uint32_t OperatorMotion::pressed_buttons(double t_s) const {
  if (!holding(t_s)) return 0;
  uint32_t pressed = 0;
  for (const ButtonPress& p : config_.presses) {
    if (t_s >= p.at_s && t_s < p.at_s + p.hold_s) pressed |= uint32_t{1} << p.button;
  }
  return pressed;
}

void OperatorMotion::sine(double t_s, JointVector& q_rad, JointVector& dq_radps) const {
  const double w = 2 * M_PI * config_.frequency_hz;
  const Ramp envelope = smoothstep(t_s, config_.ramp_s);
  for (size_t i = 0; i < config_.joints; ++i) {
    // each joint a little out of phase, so that the motion is not degenerate
    const double phase = 0.4 * static_cast<double>(i);
    const double a = config_.amplitude_rad[i];
    q_rad[i] = config_.home_rad[i] + envelope.value * a * std::sin(w * t_s + phase);
    dq_radps[i] = envelope.value * a * w * std::cos(w * t_s + phase) + envelope.rate * a * std::sin(w * t_s + phase);
  }
}

void OperatorMotion::push_hold(double t_s, JointVector& q_rad, JointVector& dq_radps) const {
  const Ramp push = smoothstep(t_s, config_.ramp_s);
  for (size_t i = 0; i < config_.joints; ++i) {
    q_rad[i] = config_.home_rad[i] + push.value * config_.amplitude_rad[i];
    dq_radps[i] = push.rate * config_.amplitude_rad[i];
  }
}

}  // namespace teleop::leader
