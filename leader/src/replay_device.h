#pragma once
// A leader device that plays a recorded joint trajectory (e.g. a recorded run's trace), so an
// experiment can be repeated with exactly the same operator motion. Replay is open loop: the
// recorded motion does not react to feedback and the device cannot render it; write() only
// checks the feedback and records the largest torque that would have been rendered.

#include <cstdint>

#include "joint_trajectory.h"
#include "teleop/leader/leader_device.h"

namespace teleop::leader {

class ReplayDevice final : public LeaderDevice {
 public:
  /// Plays `trajectory` from its start; the device time advances by `period_s` per write().
  /// Throws std::invalid_argument for a period that is not positive and finite.
  ReplayDevice(JointTrajectory trajectory, double period_s);

  size_t joints() const override { return trajectory_.joints(); }
  /// The trajectory at the device time; tau_operator_nm is 0 (no operator). Real-time safe.
  [[nodiscard]] bool read(DeviceState& state) override;
  /// Advances the device time by one period, also when the feedback is refused (the period has
  /// passed either way). False for non-finite feedback, which is not recorded. Real-time safe.
  [[nodiscard]] bool write(const JointVector& feedback_nm) override;
  const char* name() const override { return "replay"; }

  /// Device time [s] since the start of the trajectory.
  double time_s() const { return static_cast<double>(periods_) * period_s_; }
  /// The largest |feedback| of any joint accepted so far [Nm]: what a real device would have rendered.
  double max_feedback_nm() const { return max_feedback_nm_; }

 private:
  JointTrajectory trajectory_;
  double period_s_;
  uint64_t periods_ = 0;  // counted, not summed, so the time does not drift
  double max_feedback_nm_ = 0.0;
};

}  // namespace teleop::leader
