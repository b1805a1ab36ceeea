#include "teleop/hand/position_control.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace teleop::hand {

PdGains pd_gains_for(double inertia_kgm2, double bandwidth_radps, double damping_ratio) {
  const auto positive = [](double v) { return v > 0.0 && std::isfinite(v); };
  if (!positive(inertia_kgm2) || !positive(bandwidth_radps) || !positive(damping_ratio)) {
    throw std::invalid_argument("pd_gains_for: inertia, bandwidth and damping ratio must be positive and finite");
  }
  return {inertia_kgm2 * bandwidth_radps * bandwidth_radps, 2.0 * damping_ratio * inertia_kgm2 * bandwidth_radps};
}

HandPositionControl::HandPositionControl(HandPlant& plant, CouplingMode mode, double bandwidth_radps,
                                         double damping_ratio, double servo_bandwidth_radps)
    : mode_(mode) {
  const bool constraint = mode == CouplingMode::kConstraint;
  plant.set_couplings_active(constraint);
  for (size_t k = 0; k < kHandMotors; ++k) {
    motor_gains_[k] = pd_gains_for(plant.channel_inertia_kgm2(k, constraint), bandwidth_radps, damping_ratio);
  }
  if (constraint) return;
  for (size_t j = 0; j < kHandJoints; ++j) {
    if (plant.index().equality[j] >= 0) {
      joint_gains_[j] = pd_gains_for(plant.joint_inertia_kgm2(j), servo_bandwidth_radps, damping_ratio);
    }
  }
}

void HandPositionControl::apply(HandPlant& plant, const HandMotorVector& m_ref_rad,
                                const HandMotorVector& dm_ref_radps) const {
  const HandMotorVector m = plant.motor_positions();
  const HandMotorVector dm = plant.motor_velocities();
  for (size_t k = 0; k < kHandMotors; ++k) {
    plant.set_motor_torque(k, pd_torque(motor_gains_[k], m_ref_rad[k], dm_ref_radps[k], m[k], dm[k]));
  }
  if (mode_ != CouplingMode::kServo) return;
  const HandCoupling& coupling = plant.coupling();
  const HandJointVector q = plant.joint_positions();
  for (size_t j = 0; j < kHandJoints; ++j) {
    if (plant.index().equality[j] < 0) continue;
    const CouplingTerm& t = coupling.terms()[j];
    const double q_ref = t.factor * m_ref_rad[t.motor] + coupling.offsets()[j];
    const double dq_ref = t.factor * dm_ref_radps[t.motor];
    const double limit = plant.motor_torque_limit_nm(t.motor);
    const int dof = plant.index().dof[j];
    // the joint's own bias force (gravity above all): a PD designed for a few grams of finger
    // link is too soft to hold it, where the PID of a mimic-joint servo integrates it away
    const double tau =
        pd_torque(joint_gains_[j], q_ref, dq_ref, q[j], plant.joint_velocity(j)) + plant.data()->qfrc_bias[dof];
    plant.data()->qfrc_applied[dof] = std::clamp(tau, -limit, limit);
  }
}

}  // namespace teleop::hand
