#pragma once
// One joint of an arm driven by a CiA 402 drive in cyclic synchronous torque mode (mode 10), seen
// from the master: the joint's units to and from the drive's process data (encoder ticks, per
// mille of the motor's rated torque 0x6076), the walk to operation enabled, the drive's state.
// Independent of how the process data travels: over CANopen the PDOs carry it
// (canopen_arm_bus), over EtherCAT's CoE the same objects would. Plain arithmetic, real-time safe.

#include <cstdint>

#include "teleop/can/cia402.h"

namespace teleop::robot {

/// What the master knows of one joint's drive (the per-drive YAML, docs/robots.md).
struct Cia402AxisConfig {
  double gear_ratio = 1.0;             // motor revolutions per joint revolution, > 0
  double gear_efficiency = 1.0;        // joint torque = motor torque x ratio x efficiency
  double encoder_ticks_per_rev = 0.0;  // motor side, after quadrature (0x608F)
  double rated_torque_nm = 0.0;        // 0x6076, motor side (the drive's is read back and checked)
  double offset_rad = 0.0;             // the joint angle at encoder count 0 (absolute encoder)
  bool inverted = false;               // the joint turns against the motor's positive direction
  double max_torque_nm = 0.0;          // joint side: larger commands are clamped (and counted)
  double velocity_filter_hz = 200.0;   // low-pass of the rate differentiated from positions
};

/// The drive's process data the master reads (TPDOs): 0x6041, 0x6064, 0x6077, and 0x606C where
/// the bus has room for it (else the axis differentiates the positions).
struct AxisFeedback {
  uint16_t statusword = 0;
  int32_t position_ticks = 0;
  int16_t torque_permille = 0;
  bool velocity_measured = false;
  int32_t velocity_ticks_per_s = 0;
};

/// The drive's process data the master writes (RPDO): 0x6040, 0x6071.
struct AxisCommand {
  uint16_t controlword = 0;
  int16_t target_torque_permille = 0;
};

class Cia402Axis {
 public:
  /// Throws std::invalid_argument naming the first value that is not physical.
  explicit Cia402Axis(const Cia402AxisConfig& config);

  /// The drive's newest feedback, sampled `interval_s` after the one before (its SYNC period;
  /// 0 = the first, or the same sample again: no new rate).
  void take(const AxisFeedback& feedback, double interval_s = 0.0);

  /// Joint angle [rad], rate [rad/s] and the drive's torque at the joint [N m], from the feedback.
  double position_rad() const;
  double velocity_radps() const;
  double torque_nm() const;
  can::cia402::State state() const { return can::cia402::state_from_statusword(feedback_.statusword); }
  bool enabled() const { return state() == can::cia402::State::kOperationEnabled; }
  /// The drive holds in quick stop active because the master asked it to (quick_stop()).
  bool holding() const { return quick_stop_asked_ && state() == can::cia402::State::kQuickStopActive; }
  /// The drive has left operation enabled since it was enabled other than into the quick stop the
  /// master asked for: a fault, its own quick stop (a lost master), a power-off. (A fault found
  /// before the first enable is not a failure: the walk resets it.) A quick stop asked for counts
  /// as asked until the drive has reported enabled kResumeReports times in a row after the resume
  /// (its report of the quick stop may still be on its way behind an older one of enabled).
  bool failed() const;
  static constexpr unsigned kResumeReports = 16;

  /// The command for the next cycle: while not enabled, the next step of the walk to operation
  /// enabled at zero torque; from a quick stop the master asked for, enable operation at once
  /// (transition 16, with quick stop option code 6: no power-off in between) with the torque;
  /// once enabled, the joint torque within +-max_torque_nm (a clamp is counted). After a failure
  /// only quick stop: reset() lets the walk start again.
  AxisCommand command(double torque_nm);
  /// Quick stop (controlword 0x0002): the drive brakes and holds by itself, until command().
  AxisCommand quick_stop();
  /// Forgets a failure: the next command() walks the drive to operation enabled again.
  void reset();

  /// A joint torque as the drive's target (per mille of the rated torque at the motor), within
  /// +-max_torque_nm and the INTEGER16 range; `clamped` says when it was limited.
  int16_t torque_permille(double torque_nm, bool& clamped) const;
  uint64_t clamped_commands() const { return clamped_; }
  const Cia402AxisConfig& config() const { return config_; }

 private:
  double sign() const { return config_.inverted ? -1.0 : 1.0; }

  Cia402AxisConfig config_;
  double ticks_per_rad_;        // joint radians to motor encoder ticks
  double nm_per_permille_;      // one per mille of the rated torque, at the joint
  AxisFeedback feedback_;
  double velocity_radps_ = 0.0;  // measured, or differentiated and filtered
  uint16_t controlword_ = 0;
  bool quick_stop_asked_ = false;  // until the drive shows enabled after the master resumed it
  bool resume_sent_ = false;       // enable operation sent since the quick stop
  unsigned enabled_reports_ = 0;   // reports of enabled in a row since then
  bool was_enabled_ = false;
  bool failed_ = false;
  uint64_t clamped_ = 0;
};

}  // namespace teleop::robot
