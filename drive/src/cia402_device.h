#pragma once
// The CiA 402 device side of the drive: the power drive system's state machine driven by the
// controlword, the statusword, the application objects (targets, software limits, current
// limit, following error window and timeout, the abort connection option), faults with their
// EMCY, the fault reaction, the reaction to a lost master, and the demand of the cyclic
// synchronous modes: the position the servo tracks (CSP) or the current it drives (CST), and
// when the power stage is on.

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
  /// The controlword is level-triggered: evaluated again every step, unless the master was lost
  /// since it was written (a dead master's enable must not undo the drive's reaction).
  void evaluate_held_controlword();
  /// A drive fault with this EMCY code: EMCY now, fault reaction, then fault.
  void raise_fault(uint16_t error_code, const std::array<uint8_t, 5>& vendor);
  /// The power stage is on (operation enabled, or quick stop braking and holding).
  bool power_on() const;
  /// The master is lost (a consumed heartbeat timed out): EMCY 0x8130 and the reaction that
  /// 0x6007 selects.
  void connection_lost();

  // --- control, from the drive's substeps ---
  /// One position period: the servo's demand from the state, mode, target and limits (CSP: the
  /// position, with the following error monitor; CST: the current for the target torque).
  void control_position(int64_t period_ns);
  /// The fault reaction runs for its time (power already off), then the drive is in fault.
  void advance_fault_reaction(int64_t dt_ns);

  // --- objects ---
  uint8_t error_register() const { return error_register_; }
  uint16_t error_code() const { return error_code_; }
  int8_t mode() const { return mode_; }
  /// 0x6060: no mode, cyclic synchronous position or torque; anything else is refused (false).
  bool set_mode(int8_t mode);
  int32_t target_ticks() const { return target_ticks_; }
  void set_target_ticks(int32_t ticks) { target_ticks_ = ticks; }
  /// 0x6071 [per mille of 0x6076], the motor's torque in CST.
  int16_t target_torque_permille() const { return target_torque_permille_; }
  void set_target_torque_permille(int16_t permille) { target_torque_permille_ = permille; }
  /// 0x6076 [mN m]: k_t x rated current (a DC motor), at least 1.
  uint32_t rated_torque_mnm() const;
  /// 0x6007: kNoAction..kQuickStop; other codes are refused (false).
  int16_t abort_connection_option() const { return abort_connection_option_; }
  bool set_abort_connection_option(int16_t code);
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
  void evaluate_controlword(uint16_t previous);
  void enter_state(can::cia402::State next);
  void enter_fault(uint16_t error_code, const std::array<uint8_t, 5>& vendor);
  /// The target within the software limits (when they make a range); `limited` when clamped.
  int32_t target_within_limits(bool& limited) const;
  void monitor_following_error(double error_rad, int64_t period_ns);
  void control_torque();

  const EmulatedDriveConfig& config_;
  ServoController& servo_;
  const MotorModel& motor_;
  NmtSlave& nmt_;

  can::cia402::State state_ = can::cia402::State::kNotReadyToSwitchOn;
  uint16_t controlword_ = 0;
  bool controlword_stale_ = false;  // the master was lost since the controlword was written
  int8_t mode_ = can::cia402::kModeNone;
  uint8_t error_register_ = 0;
  uint16_t error_code_ = 0;
  int64_t fault_reaction_remaining_ns_ = 0;
  bool internal_limit_ = false;
  bool following_error_ = false;
  int64_t following_error_ns_ = 0;  // time the error has been above the window

  int32_t target_ticks_ = 0;
  int16_t target_torque_permille_ = 0;
  int16_t abort_connection_option_ = 0;
  uint32_t following_error_window_ticks_ = 0;
  uint16_t following_error_timeout_ms_ = 0;
  uint16_t max_current_permille_ = 0;
  int32_t limit_min_ticks_ = 0;
  int32_t limit_max_ticks_ = 0;
};

}  // namespace teleop::drive
