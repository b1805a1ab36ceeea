#pragma once
// RobotHardware on the simple joint model (independent joints, a stiff wall on joint 0): no
// gravity, so gravity compensation is nothing.

#include "teleop/follower/robot_hardware.h"

namespace teleop::follower {

class SimpleHardware final : public RobotHardware {
 public:
  /// `lever_m`: distance from joint 0 to the contact point, to express its torque as a force.
  SimpleHardware(const JointModelParams& params, const JointVector& home_rad, double period_s, double lever_m);

  size_t joints() const override { return model_.joints(); }
  [[nodiscard]] HardwareStatus read(ArmState& state) override;
  [[nodiscard]] HardwareStatus write(const JointVector& tau_nm) override;
  const char* name() const override { return "simple"; }

 private:
  JointModel model_;
  double period_s_;
  double lever_m_;
  JointVector applied_{};
};

}  // namespace teleop::follower
