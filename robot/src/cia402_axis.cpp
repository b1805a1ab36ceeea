#include "teleop/robot/cia402_axis.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace teleop::robot {

namespace cia402 = can::cia402;
using cia402::State;

namespace {

void require(bool ok, const char* key, const char* what) {
  if (!ok) throw std::invalid_argument(std::string("CiA 402 axis: ") + key + " " + what);
}

}  // namespace

Cia402Axis::Cia402Axis(const Cia402AxisConfig& config) : config_(config) {
  require(std::isfinite(config.gear_ratio) && config.gear_ratio > 0, "gear_ratio", "must be > 0");
  require(config.gear_efficiency > 0 && config.gear_efficiency <= 1, "gear_efficiency", "must be in (0, 1]");
  require(std::isfinite(config.encoder_ticks_per_rev) && config.encoder_ticks_per_rev >= 1, "encoder_ticks_per_rev",
          "must be >= 1");
  require(std::isfinite(config.rated_torque_nm) && config.rated_torque_nm > 0, "rated_torque_nm", "must be > 0");
  require(std::isfinite(config.offset_rad), "offset_rad", "must be finite");
  require(std::isfinite(config.max_torque_nm) && config.max_torque_nm > 0, "max_torque_nm", "must be > 0");
  require(std::isfinite(config.velocity_filter_hz) && config.velocity_filter_hz > 0, "velocity_filter_hz", "must be > 0");
  ticks_per_rad_ = config.encoder_ticks_per_rev * config.gear_ratio / (2.0 * M_PI);
  nm_per_permille_ = 1e-3 * config.rated_torque_nm * config.gear_ratio * config.gear_efficiency;
}

void Cia402Axis::take(const AxisFeedback& feedback, double interval_s) {
  if (feedback.velocity_measured) {
    velocity_radps_ = sign() * feedback.velocity_ticks_per_s / ticks_per_rad_;
  } else if (interval_s > 0) {
    // the sampled positions' difference, through a first-order low-pass (exact for the interval)
    const double raw = sign() * (feedback.position_ticks - feedback_.position_ticks) / ticks_per_rad_ / interval_s;
    const double alpha = 1.0 - std::exp(-2.0 * M_PI * config_.velocity_filter_hz * interval_s);
    velocity_radps_ += alpha * (raw - velocity_radps_);
  }
  feedback_ = feedback;
  const State s = state();
  if (s == State::kOperationEnabled) {
    was_enabled_ = true;
    // the quick stop is over once the drive has shown enabled kResumeReports times in a row after
    // the enable operation that ended it: the feedback lags the commands by a SYNC (by several
    // where the drives answer late), so a report of enabled from before the quick stop took effect,
    // followed by one of the quick stop itself, may still be on its way
    if (resume_sent_ && ++enabled_reports_ >= kResumeReports) quick_stop_asked_ = resume_sent_ = false;
  } else {
    enabled_reports_ = 0;
    if (was_enabled_ && !(quick_stop_asked_ && s == State::kQuickStopActive)) {
      failed_ = true;  // a fault found before the first enable is the walk's to reset
    }
  }
}

double Cia402Axis::position_rad() const {
  return config_.offset_rad + sign() * feedback_.position_ticks / ticks_per_rad_;
}
double Cia402Axis::velocity_radps() const { return velocity_radps_; }
double Cia402Axis::torque_nm() const { return sign() * feedback_.torque_permille * nm_per_permille_; }

bool Cia402Axis::failed() const { return failed_; }

int16_t Cia402Axis::torque_permille(double torque_nm, bool& clamped) const {
  const double limited = std::clamp(torque_nm, -config_.max_torque_nm, config_.max_torque_nm);
  const double permille = std::round(sign() * limited / nm_per_permille_);
  constexpr double kMax = std::numeric_limits<int16_t>::max();
  clamped = limited != torque_nm || std::fabs(permille) > kMax;
  return static_cast<int16_t>(std::clamp(permille, -kMax, kMax));
}

AxisCommand Cia402Axis::command(double torque_nm) {
  if (failed_) {
    controlword_ = cia402::controlword_for(cia402::Command::kQuickStop);
    return {controlword_, 0};
  }
  // the walk, unless enabled or holding in the quick stop asked for (a feedback one SYNC old may
  // still show enabled after the quick stop went out: the drive is taken at its word next cycle)
  if (!enabled() && !quick_stop_asked_) {
    controlword_ = cia402::next_controlword(feedback_.statusword, controlword_);
    return {controlword_, 0};
  }
  bool clamped = false;
  const int16_t permille = torque_permille(torque_nm, clamped);
  if (clamped) ++clamped_;
  controlword_ = cia402::controlword_for(cia402::Command::kEnableOperation);
  if (quick_stop_asked_) resume_sent_ = true;
  return {controlword_, permille};
}

AxisCommand Cia402Axis::quick_stop() {
  if (was_enabled_) quick_stop_asked_ = true;
  resume_sent_ = false;
  enabled_reports_ = 0;
  controlword_ = cia402::controlword_for(cia402::Command::kQuickStop);
  return {controlword_, 0};
}

void Cia402Axis::reset() {
  failed_ = false;
  was_enabled_ = false;
  quick_stop_asked_ = resume_sent_ = false;
  enabled_reports_ = 0;
}

}  // namespace teleop::robot
