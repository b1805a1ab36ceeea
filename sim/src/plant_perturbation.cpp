#include "teleop/sim/plant_perturbation.h"

#include <cmath>
#include <numbers>

namespace teleop::sim {

double SeededRandom::uniform() {
  // the top 53 bits: every double in [0, 1) on a 2^-53 grid
  return static_cast<double>(engine_() >> 11) * 0x1.0p-53;
}

double SeededRandom::gaussian() {
  if (has_spare_) {
    has_spare_ = false;
    return spare_;
  }
  // Box-Muller on (0, 1] x [0, 1): log never sees 0
  const double u1 = 1.0 - uniform();
  const double u2 = uniform();
  const double r = std::sqrt(-2.0 * std::log(u1));
  const double phi = 2.0 * std::numbers::pi * u2;
  spare_ = r * std::sin(phi);
  has_spare_ = true;
  return r * std::cos(phi);
}

uint64_t derived_seed(uint64_t seed, uint64_t stream) {
  uint64_t z = seed + (stream + 1) * 0x9E3779B97F4A7C15ULL;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

AppliedPerturbation perturb_plant(mjModel* m, mjData* d, const ActuatedJoints& joints, const PerturbationSpec& spec,
                                  uint64_t seed) {
  AppliedPerturbation out;
  out.seed = seed;
  SeededRandom random(seed);
  for (size_t i = 0; i < joints.count; ++i) {
    const int joint = m->actuator_trnid[2 * joints.actuator[i]];
    const int body = m->jnt_bodyid[joint];
    const int dof = joints.dof[i];
    // one fixed order of draws per joint, so a seed names one robot
    const double mass = 1.0 + spec.mass_fraction * random.symmetric();
    std::array<double, 3> com{};
    for (double& c : com) c = spec.com_offset_m * random.symmetric();
    const double friction = 1.0 + spec.friction_fraction * random.symmetric();
    const double damping = spec.damping_max_nms_per_rad * random.uniform();
    const double armature = 1.0 + spec.armature_fraction * random.symmetric();

    out.nominal_mass_kg += m->body_mass[body];
    m->body_mass[body] *= mass;
    out.perturbed_mass_kg += m->body_mass[body];
    for (int k = 0; k < 3; ++k) {
      m->body_inertia[3 * body + k] *= mass;
      m->body_ipos[3 * body + k] += com[static_cast<size_t>(k)];
    }
    m->dof_frictionloss[dof] *= friction;
    m->dof_damping[dof] += damping;
    m->dof_armature[dof] *= armature;

    out.mass_factor.push_back(mass);
    out.com_offset_m.push_back(com);
    out.friction_factor.push_back(friction);
    out.damping_nms_per_rad.push_back(damping);
    out.armature_factor.push_back(armature);
  }
  // subtree masses, the constraint solver's weights and the like follow the new inertias
  mj_setConst(m, d);
  return out;
}

PerturbationSpec read_perturbation(const ConfigNode& p) {
  PerturbationSpec s;
  s.mass_fraction = p.get_double("mass_fraction", Range{0, 0.9}, s.mass_fraction);
  s.com_offset_m = p.get_double("com_offset_m", Range{0, 0.1}, s.com_offset_m);
  s.friction_fraction = p.get_double("friction_fraction", Range{0, 1}, s.friction_fraction);
  s.damping_max_nms_per_rad = p.get_double("damping_max_nms_per_rad", Range{0, 100}, s.damping_max_nms_per_rad);
  s.armature_fraction = p.get_double("armature_fraction", Range{0, 0.9}, s.armature_fraction);
  return s;
}

SensorNoiseSpec read_sensor_noise(const ConfigNode& n) {
  SensorNoiseSpec s;
  s.q_rad = n.get_double("q_rad", Range{0, 0.1}, s.q_rad);
  s.dq_radps = n.get_double("dq_radps", Range{0, 10}, s.dq_radps);
  s.tau_nm = n.get_double("tau_nm", Range{0, 100}, s.tau_nm);
  return s;
}

RealRobotSpec read_real_robot(const ConfigNode& real_robot) {
  RealRobotSpec r;
  r.seed = static_cast<uint64_t>(real_robot.get_int("seed", Range{0, 9007199254740992.0}, 0));
  if (const auto p = real_robot.optional_child("perturbation")) r.perturbation = read_perturbation(*p);
  if (const auto n = real_robot.optional_child("sensor_noise")) r.sensor_noise = read_sensor_noise(*n);
  return r;
}

}  // namespace teleop::sim
