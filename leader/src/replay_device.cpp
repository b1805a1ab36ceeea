#include "replay_device.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace teleop::leader {

ReplayDevice::ReplayDevice(JointTrajectory trajectory, double period_s)
    : trajectory_(std::move(trajectory)), period_s_(period_s) {
  if (!(period_s > 0.0) || !std::isfinite(period_s))
    throw std::invalid_argument("ReplayDevice: period_s must be positive and finite, got " + std::to_string(period_s));
}

bool ReplayDevice::read(DeviceState& state) {
  trajectory_.sample(time_s(), state.q_rad, state.dq_radps);
  state.tau_operator_nm.fill(0.0);
  return true;
}

bool ReplayDevice::write(const JointVector& feedback_nm) {
  ++periods_;
  double largest_nm = 0.0;
  for (size_t j = 0; j < joints(); ++j) {
    if (!std::isfinite(feedback_nm[j])) return false;
    largest_nm = std::max(largest_nm, std::abs(feedback_nm[j]));
  }
  max_feedback_nm_ = std::max(max_feedback_nm_, largest_nm);
  return true;
}

}  // namespace teleop::leader
