#include "joint_command_law.h"

#include <algorithm>
#include <cmath>

namespace teleop::twin {

bool command_usable(const msg::JointCommand& cmd, size_t joints) {
  const auto ok = [joints](const std::vector<double>& v) {
    return v.size() == joints && std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
  };
  return ok(cmd.q_des_rad()) && ok(cmd.dq_des_radps()) && ok(cmd.tau_ff_nm()) && ok(cmd.stiffness_nm_per_rad()) &&
         ok(cmd.damping_nms_per_rad());
}

void command_torque(const msg::JointCommand& cmd, const JointVector& q_rad, size_t joints, JointVector& tau_nm,
                    JointVector& damping) {
  for (size_t i = 0; i < joints; ++i) {
    damping[i] = cmd.damping_nms_per_rad()[i];
    tau_nm[i] = cmd.stiffness_nm_per_rad()[i] * (cmd.q_des_rad()[i] - q_rad[i]) + damping[i] * cmd.dq_des_radps()[i] +
                cmd.tau_ff_nm()[i];
  }
}

}  // namespace teleop::twin
