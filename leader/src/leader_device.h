#pragma once
// The operator's input device behind an interface: a torque-controlled arm used as master that
// reports its joint state and renders feedback torques. Implementations: a simulated haptic arm
// pulled by a simulated operator (simulated_haptic_arm.h); a real device plugs in here.

#include "teleop/common/joint_model.h"

namespace teleop::leader {

struct DeviceState {
  JointVector q_rad{};
  JointVector dq_radps{};
  /// The torque the operator applies to the device, where known (simulation), else 0.
  JointVector tau_operator_nm{};
};

class LeaderDevice {
 public:
  virtual ~LeaderDevice() = default;
  virtual size_t joints() const = 0;
  /// Real-time safe. False when the device cannot be read.
  [[nodiscard]] virtual bool read(DeviceState& state) = 0;
  /// Renders `feedback_nm` for the next period. Real-time safe. False when refused.
  [[nodiscard]] virtual bool write(const JointVector& feedback_nm) = 0;
  virtual const char* name() const = 0;
};

}  // namespace teleop::leader
