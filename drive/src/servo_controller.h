#pragma once
// The cascade inside the drive: a position PID (reference step limit, anti-windup, derivative on
// a filtered velocity estimate) gives the current reference; a current PI (anti-windup) gives
// the bridge voltage. Gains are read live from the drive's configuration, which SDO writes to
// object 0x2000 change. What the position loop tracks, and when the power stage is on, the
// CiA 402 device side decides. Plain arithmetic, real-time safe.

#include "teleop/drive/emulated_drive.h"

namespace teleop::drive {

class ServoController {
 public:
  /// `gains` must outlive the controller (the drive's configuration, written by SDO).
  ServoController(const EmulatedControllerParams& gains, double supply_v, double measured_rad);

  double position_period_s() const { return gains_.substep_s * gains_.position_loop_divider; }
  double reference_rad() const { return position_.ref_rad; }
  double velocity_estimate_radps() const { return velocity_filtered_radps_; }

  // --- position loop, once per position period ---
  /// The encoder's new reading: updates the filtered velocity estimate.
  void sense(double measured_rad);
  /// Power stage off: the reference follows the link and no current is asked for.
  void follow(double measured_rad);
  /// Moves the reference towards `target_rad`, at most the reference step limit per period.
  void approach(double target_rad);
  /// Keeps the reference where it is (quick stop, no mode).
  void hold();
  struct Regulation {
    double error_rad = 0.0;  // reference - measured
    bool saturated = false;  // the current reference hit the limit
  };
  /// The PID on the reference: sets the current reference within +-current_limit_a.
  Regulation regulate(double measured_rad, double current_limit_a);
  /// Torque mode: the current reference is `current_a` within +-current_limit_a (true: clamped);
  /// the position loop rests at the link, nothing integrated.
  bool drive_current(double current_a, double current_limit_a, double measured_rad);

  // --- current loop, every substep ---
  /// The bridge voltage that drives the measured current towards the reference.
  double current_loop(double current_a);

  // --- power stage transitions ---
  /// Bumpless start: from where the link is, integrators empty.
  void start_at(double measured_rad);
  /// Holds where the link is now (quick stop).
  void hold_at(double measured_rad);
  /// Power off: no current reference, integrators empty.
  void release();
  /// Application reset (NMT reset node): the reference at the link, nothing integrated.
  void reset(double measured_rad);

 private:
  const EmulatedControllerParams& gains_;
  double supply_v_;
  double velocity_filter_alpha_;  // first-order low-pass per position period
  // the velocity estimate from the encoder's readings
  double velocity_filtered_radps_ = 0.0;
  double measured_prev_rad_;
  struct PositionLoop {
    double ref_rad = 0.0;  // the reference, moved at most one step per period
    double ref_velocity_radps = 0.0;
    double integral_a = 0.0;
  } position_;
  struct CurrentLoop {
    double ref_a = 0.0;  // the position loop's output
    double integral_v = 0.0;
  } current_;
};

}  // namespace teleop::drive
