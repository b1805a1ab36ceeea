#include "teleop/control/drift_compensation.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace teleop::control {

DriftCompensator::DriftCompensator(const DriftCompensationConfig& config) : config_(config) {
  if (config.channels == 0 || config.channels > kMaxTdpaChannels) {
    throw std::invalid_argument("drift compensation: channels must be 1.." + std::to_string(kMaxTdpaChannels));
  }
  if (!(config.time_constant_s >= 0.0) || std::isinf(config.time_constant_s)) {
    throw std::invalid_argument("drift compensation: time_constant_s must be finite and >= 0");
  }
  for (std::size_t i = 0; i < config.channels; ++i) {
    if (!(config.max_speed[i] > 0.0)) {
      throw std::invalid_argument("drift compensation: max_speed of channel " + std::to_string(i) + " must be > 0");
    }
    if (!(config.contact_force[i] > 0.0)) {
      throw std::invalid_argument("drift compensation: contact_force of channel " + std::to_string(i) + " must be > 0");
    }
  }
}

double DriftCompensator::request(std::size_t channel, double v, double f) const {
  if (config_.time_constant_s <= 0.0) return v;
  const double limit = config_.max_speed[channel];
  const double back = -std::clamp(drift_[channel] / config_.time_constant_s, -limit, limit);
  // in contact, a return against the environment's push would press harder than commanded: wait
  if (std::abs(f) > config_.contact_force[channel] && back * f < 0.0) return v;
  return v + back;
}

}  // namespace teleop::control
