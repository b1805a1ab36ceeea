#pragma once
// The CiA 402 device side of the drive: the power drive system's state machine driven by the
// controlword, the statusword, the application objects (target, software limits, current
// limit, following error window and timeout), faults with their EMCY, the fault reaction, and
// the position loop's demand: what the servo tracks and when the power stage is on.

#include <array>
#include <cstdint>

#include "motor_model.h"
#include "nmt_slave.h"
#include "servo_controller.h"
#include "teleop/can/cia402.h"
#include "teleop/drive/emulated_drive.h"

namespace teleop::drive {

class Cia402Device {
 public:
  static constexpr uint32_t kFollowingErrorOff = 0xFFFFFFFFu;

  /// Every reference must outlive the device (parts of the same drive).
  Cia402Device(const EmulatedDriveConfig& config, ServoController& servo, const MotorModel& motor, NmtSlave& nmt);

  /// Application reset: the objects' defaults, not ready to switch on.
  void reset();
  /// Initialisation is over: transition 1 to switch on disabled.
  void initialised();

  // --- state machine ---
  can::cia402::State state() const { return state_; }
  uint16_t statusword() const;
  uint16_t controlword() const { return controlword_; }
  /// A new controlword (RPDO or SDO), evaluated against the previous one (fault reset's edge).
  void set_controlword(uint16_t controlword);
  /// The controlword is level-triggered: evaluated again every step.
  void evaluate_controlword(uint16_t previous);
  /// A drive fault with this EMCY code: EMCY now, fault reaction, then fault.
  void raise_fault(uint16_t error_code, const std::array<uint8_t, 5>& vendor);
  /// The power stage is on (operation enabled, or quick stop braking and holding).
  bool power_on() const;

  // --- control, from the drive's substeps ---
  /// One position period: the servo's demand from the state, mode, target and limits, and the
  /// following error monitor.
  void control_position(int64_t period_ns);
  /// The fault reaction runs for its time (power already off), then the drive is in fault.
  void advance_fault_reaction(int64_t dt_ns);

  // --- objects ---
  uint8_t error_register() const { return error_register_; }
  uint16_t error_code() const { return error_code_; }
  int8_t mode() const { return mode_; }
  /// 0x6060: no mode or cyclic synchronous position; anything else is refused (false).
  bool set_mode(int8_t mode);
  int32_t target_ticks() const { return target_ticks_; }
  void set_target_ticks(int32_t ticks) { target_ticks_ = ticks; }
  uint32_t following_error_window_ticks() const { return following_error_window_ticks_; }
  void set_following_error_window_ticks(uint32_t ticks) { following_error_window_ticks_ = ticks; }
  uint16_t following_error_timeout_ms() const { return following_error_timeout_ms_; }
  void set_following_error_timeout_ms(uint16_t ms) { following_error_timeout_ms_ = ms; }
  uint16_t max_current_permille() const { return max_current_permille_; }
  /// 0x6073 [per mille of rated]: refused (false) above the hardware's peak current.
  bool set_max_current_permille(uint16_t permille);
  int32_t limit_min_ticks() const { return limit_min_ticks_; }
  int32_t limit_max_ticks() const { return limit_max_ticks_; }
  void set_limit_min_ticks(int32_t ticks) { limit_min_ticks_ = ticks; }
  void set_limit_max_ticks(int32_t ticks) { limit_max_ticks_ = ticks; }
  /// Current limit in force [A]: 0x6073 within the hardware peak.
  double current_limit_a() const;

 private:
  void enter_state(can::cia402::State next);
  void enter_fault(uint16_t error_code, const std::array<uint8_t, 5>& vendor);
  /// The target within the software limits (when they make a range); `limited` when clamped.
  int32_t target_within_limits(bool& limited) const;
  void monitor_following_error(double error_rad, int64_t period_ns);

  const EmulatedDriveConfig& config_;
  ServoController& servo_;
  const MotorModel& motor_;
  NmtSlave& nmt_;

  can::cia402::State state_ = can::cia402::State::kNotReadyToSwitchOn;
  uint16_t controlword_ = 0;
  int8_t mode_ = can::cia402::kModeNone;
  uint8_t error_register_ = 0;
  uint16_t error_code_ = 0;
  int64_t fault_reaction_remaining_ns_ = 0;
  bool internal_limit_ = false;
  bool following_error_ = false;
  int64_t following_error_ns_ = 0;  // time the error has been above the window

  int32_t target_ticks_ = 0;
  uint32_t following_error_window_ticks_ = 0;
  uint16_t following_error_timeout_ms_ = 0;
  uint16_t max_current_permille_ = 0;
  int32_t limit_min_ticks_ = 0;
  int32_t limit_max_ticks_ = 0;
};

}  // namespace teleop::drive
