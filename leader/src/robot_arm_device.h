#pragma once
// A torque-controlled robot arm as the operator's haptic master (the pattern of stations built
// from a second arm): any robot the follower can drive (robot::RobotHardware: an arm of CiA 402
// drives on SocketCAN, the simulation) read for its joints and given the rendered torque on top of
// its own weight, g(q) from the arm's model where the robot does not carry it itself. The torque
// never exceeds the robot's limits nor the device's own (clamped, counted). A state that is not
// current (late feedback, a drive's fault) fails the read, so the leader holds and fades its
// feedback, and the arm holds by the robot's own means meanwhile (the drives' quick stop).

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "arm_kinematics.h"
#include "teleop/leader/leader_device.h"
#include "teleop/robot/robot_hardware.h"

namespace teleop::leader {

class RobotArmDevice final : public LeaderDevice {
 public:
  /// `gravity`: the arm's model, given for (and only for) a robot that does not compensate gravity
  /// itself (throws std::invalid_argument when it is missing). `max_torque_nm`: the device's own
  /// bound per joint, within the robot's; `damping_nms_per_rad`: a viscous damping it renders.
  RobotArmDevice(std::unique_ptr<robot::RobotHardware> arm, std::unique_ptr<ArmKinematics> gravity,
                 const JointVector& max_torque_nm, const JointVector& damping_nms_per_rad);

  size_t joints() const override { return arm_->joints(); }
  /// The joints, and the external torque the robot reports as the operator's. Real-time safe.
  [[nodiscard]] bool read(DeviceState& state) override;
  /// feedback + g(q) - damping dq, clamped; or the robot's own hold while its state is not current.
  /// Real-time safe.
  [[nodiscard]] bool write(const JointVector& feedback_nm) override;
  const char* name() const override { return name_.c_str(); }
  /// The robot's counters, and arm_stale_reads, arm_fault_reads, arm_torque_clamps, arm_holds.
  void report_counters(std::vector<std::pair<std::string, double>>& counters) const override;

 private:
  std::unique_ptr<robot::RobotHardware> arm_;
  std::unique_ptr<ArmKinematics> gravity_;
  std::string name_;
  JointVector limit_nm_{};
  JointVector damping_{};
  robot::ArmState state_{};
  JointVector torque_nm_{};
  bool current_ = false;
  uint64_t stale_reads_ = 0;
  uint64_t fault_reads_ = 0;
  uint64_t torque_clamps_ = 0;
  uint64_t holds_ = 0;
};

}  // namespace teleop::leader
