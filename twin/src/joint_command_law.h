#pragma once
// The joint impedance law a torque-controlled robot applies to a JointCommand (on top of its own
// gravity compensation): tau = K (q_des - q) + D (dq_des - dq) + tau_ff.

#include <teleop/msg/arm.h>

#include "teleop/common/joint_model.h"

namespace teleop::twin {

/// True when every sequence the law reads has `joints` entries and all of them are finite.
[[nodiscard]] bool command_usable(const msg::JointCommand& cmd, size_t joints);

/// The law split for a simulation that damps implicitly: `tau_nm` = K (q_des - q) + D dq_des +
/// tau_ff and `damping` = D, the -D dq term left to the integrator. Real-time safe; `cmd` must be usable.
void command_torque(const msg::JointCommand& cmd, const JointVector& q_rad, size_t joints, JointVector& tau_nm,
                    JointVector& damping);

}  // namespace teleop::twin
