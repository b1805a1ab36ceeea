#include "teleop/hand/svh_model.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string_view>

namespace teleop::hand {
namespace {

constexpr double kPolynomialTolerance = 1e-12;

std::runtime_error model_error(const std::string& model_name, const std::string& what) {
  return std::runtime_error("MuJoCo model '" + model_name + "': " + what);
}

int find(const mjModel* m, mjtObj type, std::string_view name, const std::string& model_name, const char* kind) {
  const std::string key(name);
  const int id = mj_name2id(m, type, key.c_str());
  if (id < 0) throw model_error(model_name, std::string("no ") + kind + " '" + key + "' (the SVH-class hand's)");
  return id;
}

// the equality whose joint1 is `joint_id`; -1 when there is none
int equality_on(const mjModel* m, int joint_id) {
  for (int e = 0; e < m->neq; ++e) {
    if (m->eq_type[e] == mjEQ_JOINT && m->eq_obj1id[e] == joint_id) return e;
  }
  return -1;
}

void check_equality(const mjModel* m, const std::string& model_name, const SvhModelIndex& index,
                    const CouplingPolynomial& p) {
  const std::string name(kHandJointNames[p.joint]);
  const int e = index.equality[p.joint];
  if (e < 0) throw model_error(model_name, "no joint equality on coupled joint '" + name + "'");
  const std::string main(kHandJointNames[p.main_joint]);
  if (m->eq_obj2id[e] != index.joint_id[p.main_joint]) {
    throw model_error(model_name, "the equality on '" + name + "' does not tie it to '" + main + "'");
  }
  const mjtNum* data = m->eq_data + static_cast<ptrdiff_t>(e) * mjNEQDATA;
  const bool same = std::abs(data[0] - p.c0_rad) <= kPolynomialTolerance &&
                    std::abs(data[1] - p.c1) <= kPolynomialTolerance && data[2] == 0.0 && data[3] == 0.0 &&
                    data[4] == 0.0;
  if (!same) {
    throw model_error(model_name, "the equality on '" + name + "' has polycoef (" + std::to_string(data[0]) + ", " +
                                      std::to_string(data[1]) + ", " + std::to_string(data[2]) + ", ...), the " +
                                      "coupling table (hand_coupling.cpp) says (" + std::to_string(p.c0_rad) + ", " +
                                      std::to_string(p.c1) + ", 0, 0, 0)");
  }
}

}  // namespace

size_t main_joint_of(size_t motor) {
  for (size_t j = 0; j < kHandJoints; ++j) {
    if (kHandJointNames[j] == kHandMotorNames.at(motor)) return j;
  }
  throw std::logic_error("hand_coupling.cpp: motor " + std::to_string(motor) + " has no joint of its name");
}

CouplingPolynomial coupling_polynomial(const HandCoupling& coupling, size_t joint) {
  const CouplingTerm& term = coupling.terms().at(joint);
  CouplingPolynomial p;
  p.joint = joint;
  p.main_joint = main_joint_of(term.motor);
  const CouplingTerm& main = coupling.terms()[p.main_joint];
  // m = (q_main - q0_main) / f_main, so q_j = f_j / f_main q_main + q0_j - f_j / f_main q0_main
  p.c1 = term.factor / main.factor;
  p.c0_rad = coupling.offsets()[joint] - p.c1 * coupling.offsets()[p.main_joint];
  return p;
}

SvhModelIndex index_svh_model(const mjModel* m, const std::string& model_name, const HandCoupling& coupling) {
  SvhModelIndex index;
  for (size_t j = 0; j < kHandJoints; ++j) {
    const int id = find(m, mjOBJ_JOINT, kHandJointNames[j], model_name, "joint");
    const std::string name(kHandJointNames[j]);
    if (m->jnt_type[id] != mjJNT_HINGE || !m->jnt_limited[id]) {
      throw model_error(model_name, "joint '" + name + "' must be a limited hinge");
    }
    index.joint_id[j] = id;
    index.qpos[j] = m->jnt_qposadr[id];
    index.dof[j] = m->jnt_dofadr[id];
    // MuJoCo's joint equality is relative to qpos0: only with qpos0 = 0 is polycoef the table's
    if (m->qpos0[index.qpos[j]] != 0.0) throw model_error(model_name, "joint '" + name + "' has a non-zero ref");
    index.equality[j] = equality_on(m, id);
  }
  index.motor_min_rad.fill(-std::numeric_limits<double>::infinity());
  index.motor_max_rad.fill(std::numeric_limits<double>::infinity());
  for (size_t j = 0; j < kHandJoints; ++j) {
    const CouplingTerm& t = coupling.terms()[j];
    const mjtNum* range = m->jnt_range + 2 * index.joint_id[j];
    // q_j = f m + q0 inside [lo, hi]: m between (lo - q0) / f and (hi - q0) / f
    const double a = (range[0] - coupling.offsets()[j]) / t.factor;
    const double b = (range[1] - coupling.offsets()[j]) / t.factor;
    index.motor_min_rad[t.motor] = std::max(index.motor_min_rad[t.motor], std::min(a, b));
    index.motor_max_rad[t.motor] = std::min(index.motor_max_rad[t.motor], std::max(a, b));
    if (j == main_joint_of(t.motor)) {
      if (index.equality[j] >= 0) {
        throw model_error(model_name, "main joint '" + std::string(kHandJointNames[j]) + "' is itself coupled");
      }
    } else {
      check_equality(m, model_name, index, coupling_polynomial(coupling, j));
    }
  }
  for (size_t k = 0; k < kHandMotors; ++k) {
    const int a = find(m, mjOBJ_ACTUATOR, kHandMotorNames[k], model_name, "actuator");
    const int main = index.joint_id[main_joint_of(k)];
    if (m->actuator_trntype[a] != mjTRN_JOINT || m->actuator_trnid[2 * a] != main || m->actuator_gear[6 * a] != 1.0) {
      throw model_error(model_name, "actuator '" + std::string(kHandMotorNames[k]) + "' must drive joint '" +
                                        std::string(kHandMotorNames[k]) + "' with gear 1");
    }
    index.actuator[k] = a;
    index.main_joint[k] = main_joint_of(k);
    if (!(index.motor_min_rad[k] < index.motor_max_rad[k])) {
      throw model_error(model_name, "the joints of motor '" + std::string(kHandMotorNames[k]) +
                                        "' leave it no range (their limits and the coupling disagree)");
    }
  }
  const int touch = find(m, mjOBJ_SENSOR, "index_tip_touch", model_name, "sensor");
  if (m->sensor_type[touch] != mjSENS_TOUCH)
    throw model_error(model_name, "sensor 'index_tip_touch' is no touch sensor");
  index.tip_touch_address = m->sensor_adr[touch];
  return index;
}

}  // namespace teleop::hand
