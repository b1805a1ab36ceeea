#include "teleop/hand/hand_plant.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

namespace teleop::hand {

HandPlant::HandPlant(sim::MujocoModel model, const HandCoupling& coupling)
    : model_(std::move(model)), coupling_(coupling), index_(index_svh_model(model_.model(), model_.path(), coupling)) {
  for (size_t j = 0; j < kHandJoints; ++j) polynomial_[j] = coupling_polynomial(coupling_, j);
  if (model_.model()->opt.integrator != mjINT_EULER) {
    throw std::runtime_error("MuJoCo model '" + model_.path() + "': HandPlant steps with mj_step1/mj_step2, which " +
                             "needs the Euler integrator");
  }
}

void HandPlant::begin_step() { mj_step1(model(), data()); }

void HandPlant::end_step() { mj_step2(model(), data()); }

void HandPlant::set_motor_torque(size_t motor, double torque_nm) { data()->ctrl[index_.actuator[motor]] = torque_nm; }

HandMotorVector HandPlant::motor_positions() const {
  HandMotorVector m_rad{};
  for (size_t k = 0; k < kHandMotors; ++k) {
    const size_t j = index_.main_joint[k];
    m_rad[k] = (data()->qpos[index_.qpos[j]] - coupling_.offsets()[j]) / coupling_.terms()[j].factor;
  }
  return m_rad;
}

HandMotorVector HandPlant::motor_velocities() const {
  HandMotorVector dm_radps{};
  for (size_t k = 0; k < kHandMotors; ++k) {
    const size_t j = index_.main_joint[k];
    dm_radps[k] = data()->qvel[index_.dof[j]] / coupling_.terms()[j].factor;
  }
  return dm_radps;
}

HandJointVector HandPlant::joint_positions() const {
  HandJointVector q_rad{};
  for (size_t j = 0; j < kHandJoints; ++j) q_rad[j] = data()->qpos[index_.qpos[j]];
  return q_rad;
}

double HandPlant::joint_velocity(size_t joint) const { return data()->qvel[index_.dof.at(joint)]; }

double HandPlant::tip_force_n() const { return data()->sensordata[index_.tip_touch_address]; }

double HandPlant::coupling_residual_rad() const {
  double worst = 0.0;
  for (size_t j = 0; j < kHandJoints; ++j) {
    if (index_.equality[j] < 0) continue;
    const CouplingPolynomial& p = polynomial_[j];
    const double expected = p.c0_rad + p.c1 * data()->qpos[index_.qpos[p.main_joint]];
    worst = std::max(worst, std::abs(data()->qpos[index_.qpos[j]] - expected));
  }
  return worst;
}

int HandPlant::mujoco_warnings() const {
  int count = 0;
  for (const mjWarningStat& w : data()->warning) count += w.number;
  return count;
}

void HandPlant::set_couplings_active(bool active) {
  for (const int e : index_.equality) {
    if (e >= 0) model()->eq_active[e] = active ? 1 : 0;
  }
}

bool HandPlant::couplings_active() const {
  for (const int e : index_.equality) {
    if (e >= 0 && model()->eq_active[e] == 0) return false;
  }
  return true;
}

void HandPlant::set_link_inertia(double inertia_kgm2) {
  if (!(inertia_kgm2 > 0.0) || !std::isfinite(inertia_kgm2)) {
    throw std::invalid_argument("HandPlant: link inertia must be positive and finite");
  }
  for (const int id : index_.joint_id) {
    mjtNum* inertia = model()->body_inertia + 3 * model()->jnt_bodyid[id];
    std::fill(inertia, inertia + 3, inertia_kgm2);
  }
  // body_invweight0, dof_invweight0 and the like scale the constraints' softness: recompute them
  mj_setConst(model(), data());
}

double HandPlant::channel_inertia_kgm2(size_t motor, bool through_couplings) const {
  const size_t main = main_joint_of(motor);
  if (!through_couplings) return joint_inertia_kgm2(main);
  // s: the joint motion per unit motion of the main joint, over all dofs of the model
  std::vector<mjtNum> s(static_cast<size_t>(model()->nv), 0.0);
  std::vector<mjtNum> ms(s.size(), 0.0);
  for (size_t j = 0; j < kHandJoints; ++j) {
    if (polynomial_[j].main_joint == main) s[static_cast<size_t>(index_.dof[j])] = j == main ? 1.0 : polynomial_[j].c1;
  }
  mj_mulM(model(), data(), ms.data(), s.data());
  return mju_dot(s.data(), ms.data(), model()->nv);
}

double HandPlant::joint_inertia_kgm2(size_t joint) const {
  // 1 / (M^-1)_jj: what the joint feels with every other joint free to move (the smallest
  // inertia a PD on it meets; M_jj would be with all others held)
  const size_t dof = static_cast<size_t>(index_.dof.at(joint));
  std::vector<mjtNum> x(static_cast<size_t>(model()->nv), 0.0);
  x[dof] = 1.0;
  // MuJoCo 2.2 declares mj_solveM with a mutable mjData; it only reads the factorised M (qLD)
  mj_solveM(model(), const_cast<mjData*>(data()), x.data(), x.data(), 1);
  return 1.0 / x[dof];
}

double HandPlant::motor_torque_limit_nm(size_t motor) const {
  const int a = index_.actuator.at(motor);
  if (!model()->actuator_ctrllimited[a]) return mjMAXVAL;
  return std::min(std::abs(model()->actuator_ctrlrange[2 * a]), std::abs(model()->actuator_ctrlrange[2 * a + 1]));
}

void HandPlant::set_motor_torque_limit(double limit_nm) {
  if (!(limit_nm > 0.0) || !std::isfinite(limit_nm)) throw std::invalid_argument("HandPlant: torque limit must be > 0");
  for (const int a : index_.actuator) {
    model()->actuator_ctrllimited[a] = 1;
    model()->actuator_ctrlrange[2 * a] = -limit_nm;
    model()->actuator_ctrlrange[2 * a + 1] = limit_nm;
  }
}

}  // namespace teleop::hand
