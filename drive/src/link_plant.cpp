#include "link_plant.h"

#include <algorithm>

namespace teleop::drive {

LinkPlant::LinkPlant(const EmulatedMotorParams& params, double initial_position_rad)
    : params_(params),
      // the rotor's inertia appears at the output multiplied by the square of the gear ratio
      inertia_kgm2_(params.link_inertia_kgm2 + params.rotor_inertia_kgm2 * params.gear_ratio * params.gear_ratio),
      q_rad_(initial_position_rad) {}

void LinkPlant::apply(double torque_nm, double dt_s, bool jammed) {
  const EmulatedMotorParams& m = params_;
  if (jammed) {
    dq_radps_ = 0;
    return;
  }
  // J ddq = tau - b dq + hard stops (a penalty spring-damper that only pushes)
  double torque = torque_nm - m.viscous_nms_per_rad * dq_radps_;
  if (q_rad_ > m.stop_max_rad) {
    torque += std::min(
        0.0, -m.stop_stiffness_nm_per_rad * (q_rad_ - m.stop_max_rad) - m.stop_damping_nms_per_rad * dq_radps_);
  } else if (q_rad_ < m.stop_min_rad) {
    torque += std::max(
        0.0, -m.stop_stiffness_nm_per_rad * (q_rad_ - m.stop_min_rad) - m.stop_damping_nms_per_rad * dq_radps_);
  }
  dq_radps_ += torque / inertia_kgm2_ * dt_s;
  q_rad_ += dq_radps_ * dt_s;
}

}  // namespace teleop::drive
