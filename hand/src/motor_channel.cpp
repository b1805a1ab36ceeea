#include "teleop/hand/motor_channel.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace teleop::hand {

using can::CanError;
using can::Result;
namespace {

bool positive_finite(double v) { return std::isfinite(v) && v > 0; }

// rounds to the nearest integer if it fits INTEGER32
Result<int32_t> to_int32(double v) {
  if (!std::isfinite(v)) return CanError::kValueOutOfRange;
  const double r = std::nearbyint(v);
  if (r < static_cast<double>(std::numeric_limits<int32_t>::min()) ||
      r > static_cast<double>(std::numeric_limits<int32_t>::max())) {
    return CanError::kValueOutOfRange;
  }
  return static_cast<int32_t>(r);
}

}  // namespace

MotorChannel::MotorChannel(const MotorChannelConfig& config) : config_(config) {
  if (!positive_finite(config.ticks_per_rev)) throw std::invalid_argument("MotorChannel: ticks_per_rev must be > 0");
  if (!positive_finite(config.gear_ratio)) throw std::invalid_argument("MotorChannel: gear_ratio must be > 0");
  if (config.sign != 1 && config.sign != -1) {
    throw std::invalid_argument("MotorChannel: sign must be +1 or -1, got " + std::to_string(config.sign));
  }
  if (!std::isfinite(config.offset_rad)) throw std::invalid_argument("MotorChannel: offset_rad must be finite");
  if (!positive_finite(config.rated_current_a)) {
    throw std::invalid_argument("MotorChannel: rated_current_a must be > 0");
  }
  rad_per_tick_ = 2.0 * M_PI / (config.ticks_per_rev * config.gear_ratio);
}

double MotorChannel::ticks_to_rad(int32_t ticks) const {
  return config_.sign * static_cast<double>(ticks) * rad_per_tick_ + config_.offset_rad;
}

Result<int32_t> MotorChannel::rad_to_ticks(double rad) const {
  return to_int32((rad - config_.offset_rad) / rad_per_tick_ * config_.sign);
}

double MotorChannel::ticks_per_s_to_radps(int32_t ticks_per_s) const {
  return config_.sign * static_cast<double>(ticks_per_s) * rad_per_tick_;
}

Result<int32_t> MotorChannel::radps_to_ticks_per_s(double radps) const {
  return to_int32(radps / rad_per_tick_ * config_.sign);
}

double MotorChannel::permille_to_amps(int16_t permille) const {
  return config_.sign * static_cast<double>(permille) * 1e-3 * config_.rated_current_a;
}

Result<uint16_t> MotorChannel::amps_to_max_current_permille(double amps) const {
  if (!std::isfinite(amps) || amps < 0) return CanError::kValueOutOfRange;
  const double permille = std::nearbyint(amps / config_.rated_current_a * 1e3);
  if (permille > std::numeric_limits<uint16_t>::max()) return CanError::kValueOutOfRange;
  return static_cast<uint16_t>(permille);
}

}  // namespace teleop::hand
