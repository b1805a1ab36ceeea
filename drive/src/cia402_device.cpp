#include "cia402_device.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace teleop::drive {

namespace cia402 = can::cia402;
using cia402::State;

Cia402Device::Cia402Device(const EmulatedDriveConfig& config, ServoController& servo, const MotorModel& motor,
                           NmtSlave& nmt)
    : config_(config), servo_(servo), motor_(motor), nmt_(nmt) {}

void Cia402Device::reset() {
  error_register_ = 0;
  error_code_ = 0;
  controlword_ = 0;
  controlword_stale_ = false;
  mode_ = cia402::kModeNone;
  target_ticks_ = 0;
  target_torque_permille_ = 0;
  abort_connection_option_ = config_.abort_connection_option;
  const double window_ticks = config_.following_error_window_rad * motor_.ticks_per_rad();
  following_error_window_ticks_ = window_ticks >= static_cast<double>(kFollowingErrorOff)
                                      ? kFollowingErrorOff
                                      : static_cast<uint32_t>(window_ticks);
  following_error_timeout_ms_ = config_.following_error_timeout_ms;
  max_current_permille_ = static_cast<uint16_t>(std::lround(config_.max_current_a / config_.rated_current_a * 1e3));
  limit_min_ticks_ = std::numeric_limits<int32_t>::min();
  limit_max_ticks_ = std::numeric_limits<int32_t>::max();
  state_ = State::kNotReadyToSwitchOn;
  fault_reaction_remaining_ns_ = 0;
  internal_limit_ = false;
  following_error_ = false;
  following_error_ns_ = 0;
}

void Cia402Device::initialised() {
  if (state_ == State::kNotReadyToSwitchOn) enter_state(State::kSwitchOnDisabled);  // transition 1
}

uint16_t Cia402Device::statusword() const {
  uint16_t s = cia402::statusword_for(state_) | cia402::sw::kRemote;
  if (state_ != State::kNotReadyToSwitchOn) s |= cia402::sw::kVoltageEnabled;
  if (internal_limit_) s |= cia402::sw::kInternalLimitActive;
  if (following_error_) s |= cia402::sw::kFollowingError;
  if (state_ == State::kOperationEnabled && mode_ != cia402::kModeNone) s |= cia402::sw::kDriveFollowsCommand;
  return s;
}

void Cia402Device::set_controlword(uint16_t controlword) {
  const uint16_t previous = controlword_;
  controlword_ = controlword;
  controlword_stale_ = false;
  evaluate_controlword(previous);
}

void Cia402Device::evaluate_held_controlword() {
  if (!controlword_stale_) evaluate_controlword(controlword_);
}

void Cia402Device::evaluate_controlword(uint16_t previous) {
  if (nmt_.initialising()) return;
  const cia402::Command command = cia402::command_from_controlword(controlword_, previous);
  const State next = cia402::next_state(state_, command);
  if (next == state_) return;
  if (state_ == State::kFault) {
    // transition 15: the error is acknowledged; CiA 301 announces it with error code 0
    error_code_ = 0;
    error_register_ = 0;
    following_error_ = false;
    following_error_ns_ = 0;
    nmt_.send_emcy(can::emcy::kErrorReset, 0, {});
  }
  enter_state(next);
}

void Cia402Device::raise_fault(uint16_t error_code, const std::array<uint8_t, 5>& vendor) {
  enter_fault(error_code, vendor);
}

void Cia402Device::connection_lost() {
  namespace option = cia402::abort_connection;
  controlword_stale_ = true;
  if (abort_connection_option_ == option::kFault) {
    enter_fault(can::emcy::kHeartbeatError, {});
    return;
  }
  nmt_.send_emcy(can::emcy::kHeartbeatError, can::error_register_for(can::emcy::kHeartbeatError), {});
  if (abort_connection_option_ == option::kDisableVoltage) {
    enter_state(cia402::next_state(state_, cia402::Command::kDisableVoltage));
  } else if (abort_connection_option_ == option::kQuickStop) {
    enter_state(cia402::next_state(state_, cia402::Command::kQuickStop));
  }
}

bool Cia402Device::power_on() const { return state_ == State::kOperationEnabled || state_ == State::kQuickStopActive; }

void Cia402Device::enter_state(State next) {
  if (next == state_) return;
  const bool was_powered = power_on();
  state_ = next;
  const double measured = motor_.measured_rad();
  if (power_on() && !was_powered) {
    servo_.start_at(measured);  // bumpless start from where the link is
    following_error_ns_ = 0;
  }
  if (next == State::kQuickStopActive) servo_.hold_at(measured);  // hold where the quick stop found it
  if (next == State::kFaultReactionActive) {
    fault_reaction_remaining_ns_ = std::llround(config_.fault_reaction_time_s * 1e9);
  }
  if (!power_on()) {
    servo_.release();
    internal_limit_ = false;
  }
}

void Cia402Device::enter_fault(uint16_t error_code, const std::array<uint8_t, 5>& vendor) {
  error_code_ = error_code;
  error_register_ = can::error_register_for(error_code);
  nmt_.send_emcy(error_code, error_register_, vendor);
  if (state_ != State::kFault && state_ != State::kFaultReactionActive) enter_state(State::kFaultReactionActive);
}

void Cia402Device::control_position(int64_t period_ns) {
  // the drive sees the link through its encoder
  const double measured = motor_.measured_rad();
  servo_.sense(measured);
  if (!power_on()) {
    servo_.follow(measured);
    return;
  }
  if (state_ == State::kOperationEnabled && mode_ == cia402::kModeCyclicSynchronousTorque) {
    control_torque();
    return;
  }
  // the reference: the target within the software limits in CSP, else held (quick stop, no mode)
  bool limited = false;
  if (state_ == State::kOperationEnabled && mode_ == cia402::kModeCyclicSynchronousPosition) {
    servo_.approach(target_within_limits(limited) / motor_.ticks_per_rad());
  } else {
    servo_.hold();
  }
  const ServoController::Regulation regulation = servo_.regulate(measured, current_limit_a());
  internal_limit_ = limited || regulation.saturated;
  monitor_following_error(regulation.error_rad, period_ns);
}

// CST: the current that makes the target torque; the position loop rests at the link, so that
// a quick stop holds from where it finds it
void Cia402Device::control_torque() {
  const double motor_torque_nm = target_torque_permille_ * 1e-3 * rated_torque_mnm() * 1e-3;
  internal_limit_ = servo_.drive_current(motor_torque_nm / config_.motor.torque_constant_nm_per_a, current_limit_a(),
                                         motor_.measured_rad());
  following_error_ns_ = 0;
}

int32_t Cia402Device::target_within_limits(bool& limited) const {
  int32_t target = target_ticks_;
  if (limit_min_ticks_ < limit_max_ticks_) {
    if (target < limit_min_ticks_) {
      target = limit_min_ticks_;
      limited = true;
    } else if (target > limit_max_ticks_) {
      target = limit_max_ticks_;
      limited = true;
    }
  }
  return target;
}

// following error: the link stays too far from the demand for too long
void Cia402Device::monitor_following_error(double error_rad, int64_t period_ns) {
  if (following_error_window_ticks_ != kFollowingErrorOff &&
      std::fabs(error_rad) * motor_.ticks_per_rad() > static_cast<double>(following_error_window_ticks_)) {
    following_error_ns_ += period_ns;
    if (following_error_ns_ >= int64_t{following_error_timeout_ms_} * 1'000'000 && !following_error_) {
      following_error_ = true;
      enter_fault(can::emcy::kFollowingError, {});
    }
  } else {
    following_error_ns_ = 0;
  }
}

void Cia402Device::advance_fault_reaction(int64_t dt_ns) {
  if (state_ != State::kFaultReactionActive) return;
  fault_reaction_remaining_ns_ -= dt_ns;
  if (fault_reaction_remaining_ns_ <= 0) enter_state(State::kFault);
}

bool Cia402Device::set_mode(int8_t mode) {
  if (mode != cia402::kModeNone && mode != cia402::kModeCyclicSynchronousPosition &&
      mode != cia402::kModeCyclicSynchronousTorque) {
    return false;
  }
  mode_ = mode;
  return true;
}

uint32_t Cia402Device::rated_torque_mnm() const {
  const double mnm = config_.motor.torque_constant_nm_per_a * config_.rated_current_a * 1e3;
  return std::max<uint32_t>(1, static_cast<uint32_t>(std::lround(mnm)));
}

bool Cia402Device::set_abort_connection_option(int16_t code) {
  if (code < cia402::abort_connection::kNoAction || code > cia402::abort_connection::kQuickStop) return false;
  abort_connection_option_ = code;
  return true;
}

bool Cia402Device::set_max_current_permille(uint16_t permille) {
  const double peak_permille = config_.peak_current_a / config_.rated_current_a * 1e3;
  if (static_cast<double>(permille) > peak_permille + 0.5) return false;
  max_current_permille_ = permille;
  return true;
}

double Cia402Device::current_limit_a() const {
  return std::min(max_current_permille_ * 1e-3 * config_.rated_current_a, config_.peak_current_a);
}

}  // namespace teleop::drive
