#include "hil_controller.h"

#include <algorithm>
#include <cmath>

#include "teleop/transport/joint_fields.h"

namespace teleop::twin {

HilController::HilController(const HilConfig& config, size_t joints) : config_(config), joints_(joints) {}

void HilController::presize(msg::JointCommand& cmd) const {
  transport::presize(joints_, cmd.q_des_rad(), cmd.dq_des_radps(), cmd.tau_ff_nm(), cmd.stiffness_nm_per_rad(),
                     cmd.damping_nms_per_rad());
  cmd.mode().assign(joints_, msg::CONTROL_JOINT_IMPEDANCE);
}

void HilController::compute(const JointVector& q_rad, double t_s, msg::JointCommand& cmd) {
  if (!started_) {
    start_rad_ = q_rad;
    started_ = true;
  }
  // smoothstep in time: zero velocity at both ends
  const double tau = std::clamp(t_s / config_.move_time_s, 0.0, 1.0);
  const double s = tau * tau * (3.0 - 2.0 * tau);
  const double ds = 6.0 * tau * (1.0 - tau) / config_.move_time_s;
  for (size_t i = 0; i < joints_; ++i) {
    const double span = config_.goal_rad[i] - start_rad_[i];
    cmd.q_des_rad()[i] = start_rad_[i] + span * s;
    cmd.dq_des_radps()[i] = span * ds;
    cmd.tau_ff_nm()[i] = 0.0;
    cmd.stiffness_nm_per_rad()[i] = config_.stiffness_nm_per_rad;
    cmd.damping_nms_per_rad()[i] = config_.damping_nms_per_rad;
  }
}

double HilController::goal_error_rad(const JointVector& q_rad) const {
  double worst = 0.0;
  for (size_t i = 0; i < joints_; ++i) worst = std::max(worst, std::abs(config_.goal_rad[i] - q_rad[i]));
  return worst;
}

}  // namespace teleop::twin
