#include "teleop/control/controller_switch.h"

#include <algorithm>
#include <stdexcept>

namespace teleop::control {

ControllerSwitch::ControllerSwitch(double cycle_s, double blend_s)
    : step_(blend_s > cycle_s ? cycle_s / blend_s : 1.0) {
  if (!(cycle_s > 0)) throw std::invalid_argument("ControllerSwitch: cycle_s must be positive");
}

int ControllerSwitch::add(Controller& controller) {
  if (count_ >= kMaxModes) throw std::length_error("ControllerSwitch: too many modes");
  modes_[static_cast<std::size_t>(count_)] = &controller;
  return count_++;
}

void ControllerSwitch::select(int mode) {
  if (mode < 0 || mode >= count_ || mode == to_) return;
  if (!have_output_) {
    // nothing has been commanded yet: there is no torque to blend from
    from_ = to_ = mode;
    return;
  }
  if (blending() && have_output_) {
    need_offset_ = true;  // delta = last output - tau of the old target, taken at the next compute
  } else {
    offset_.setZero();
    need_offset_ = false;
  }
  from_ = to_;
  to_ = mode;
  alpha_ = 0.0;
}

JointVector ControllerSwitch::compute(const ArmState& state, const ArmCommand& command) {
  const JointVector tau_to = modes_[static_cast<std::size_t>(to_)]->compute(state, command);
  if (from_ == to_) {
    last_ = tau_to;
    have_output_ = true;
    return last_;
  }
  const JointVector tau_from = modes_[static_cast<std::size_t>(from_)]->compute(state, command);
  if (need_offset_) {
    offset_ = last_ - tau_from;
    need_offset_ = false;
  }
  alpha_ = std::min(1.0, alpha_ + step_);
  last_ = (1.0 - alpha_) * (tau_from + offset_) + alpha_ * tau_to;
  if (alpha_ >= 1.0) {
    from_ = to_;
    offset_.setZero();
  }
  have_output_ = true;
  return last_;
}

}  // namespace teleop::control
