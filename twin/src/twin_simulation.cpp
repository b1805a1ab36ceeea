#include "teleop/twin/twin_simulation.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace teleop::twin {
namespace {

// collision bit of the margins: no model uses it (parts/common.xml uses 1, 2, 4, 8)
constexpr int kMarginBit = 16;

std::string margin_attributes(double activation_m) {
  std::ostringstream a;
  a.precision(17);
  a << "contype=\"" << kMarginBit << "\" conaffinity=\"" << kMarginBit
    << "\" condim=\"1\" density=\"0\" group=\"4\" solref=\"0.004 1\" rgba=\"1 0.5 0 0.3\" margin=\""
    << activation_m << "\"";
  return a.str();
}

int substeps_of(const mjModel* m, double period_s, const std::string& path) {
  if (period_s <= 0) return 1;
  const double steps = period_s / m->opt.timestep;
  const int n = static_cast<int>(std::lround(steps));
  if (n < 1 || std::abs(steps - n) > 1e-6) {
    throw std::runtime_error(path + ": timestep " + std::to_string(m->opt.timestep) +
                             " s does not divide the control period " + std::to_string(period_s) + " s");
  }
  return n;
}

// every arm's joints one after the other; without prefixes all actuated hinges, as one arm
sim::ActuatedJoints find_driven_joints(const mjModel* m, const TwinModelConfig& config) {
  if (config.joint_prefixes.empty()) return sim::find_actuated_joints(m, config.model_path);
  sim::ActuatedJoints all;
  for (const std::string& prefix : config.joint_prefixes) {
    const sim::ActuatedJoints arm = sim::find_actuated_joints(m, config.model_path, prefix);
    if (all.count + arm.count > kMaxJoints) throw std::runtime_error(config.model_path + ": too many driven joints");
    std::copy_n(arm.qpos.begin(), arm.count, all.qpos.begin() + all.count);
    std::copy_n(arm.dof.begin(), arm.count, all.dof.begin() + all.count);
    std::copy_n(arm.actuator.begin(), arm.count, all.actuator.begin() + all.count);
    all.count += arm.count;
  }
  return all;
}

}  // namespace

std::vector<sim::ModelAddition> margin_geometry(const TwinModelConfig& config) {
  std::vector<sim::ModelAddition> additions;
  for (const MarginSphere& s : config.margin_spheres) {
    std::ostringstream g;
    g.precision(17);
    g << "<geom name=\"" << s.name << "\" type=\"sphere\" size=\"" << s.radius_m << "\" pos=\"" << s.pos_m[0] << ' '
      << s.pos_m[1] << ' ' << s.pos_m[2] << "\" " << margin_attributes(config.margin_activation_m) << "/>";
    additions.push_back({s.body, g.str()});
  }
  for (const MarginPlane& p : config.margin_planes) {
    std::ostringstream g;
    g.precision(17);
    g << "<geom name=\"" << p.name << "\" type=\"plane\" size=\"2 2 0.1\" pos=\"" << p.point_m[0] << ' ' << p.point_m[1]
      << ' ' << p.point_m[2] << "\" zaxis=\"" << p.normal[0] << ' ' << p.normal[1] << ' ' << p.normal[2] << "\" "
      << margin_attributes(config.margin_activation_m) << "/>";
    additions.push_back({"", g.str()});
  }
  return additions;
}

TwinSimulation::TwinSimulation(const TwinModelConfig& config)
    : config_(config),
      sim_(sim::load_with_additions(config.model_path, margin_geometry(config))),
      joints_(find_driven_joints(sim_.model(), config)),
      contacts_(sim_.model(), config.contact_pairs, config.model_path),
      distances_(sim_.model(), config.distance_pairs, config.model_path),
      substeps_(substeps_of(sim_.model(), config.period_s, config.model_path)),
      efc_rendered_(static_cast<size_t>(std::max(sim_.model()->njmax, 1))),
      qfrc_rendered_(static_cast<size_t>(sim_.model()->nv)) {
  for (size_t i = 0; i < joints_.count; ++i) model_damping_[i] = sim_.model()->dof_damping[joints_.dof[i]];
  apply_geom_offsets();
  reset();
}

void TwinSimulation::apply_geom_offsets() {
  mjModel* m = sim_.model();
  for (const GeomOffset& o : config_.geom_offsets) {
    // throws std::out_of_range naming the model file and the geom
    const int g = sim_.geom_id(o.geom);
    for (int k = 0; k < 3; ++k) m->geom_pos[3 * g + k] += o.offset_m[static_cast<size_t>(k)];
  }
}

void TwinSimulation::set_geom_position(int geom, const std::array<double, 3>& pos_m) {
  // mj_kinematics places every geom from geom_pos each step, static ones of the world body too
  std::copy(pos_m.begin(), pos_m.end(), sim_.model()->geom_pos + 3 * geom);
}

void TwinSimulation::reset() {
  if (config_.keyframe.empty()) {
    sim_.reset();
  } else {
    sim_.reset(config_.keyframe);
  }
  tau_.fill(0.0);
  constraint_.fill(0.0);
  read_back();
}

template <typename TorqueLaw>
void TwinSimulation::advance(TorqueLaw&& law) {
  const mjModel* m = sim_.model();
  mjData* d = sim_.data();
  for (int s = 0; s < substeps_; ++s) {
    // step1 computes the bias forces of this state; the torque goes in before step2 integrates
    mj_step1(m, d);
    for (size_t i = 0; i < joints_.count; ++i) {
      tau_[i] = law(i, d->qpos[joints_.qpos[i]], d->qvel[joints_.dof[i]]);
      d->qfrc_applied[joints_.dof[i]] = tau_[i] + d->qfrc_bias[joints_.dof[i]];
    }
    mj_step2(m, d);
  }
  read_back();
}

void TwinSimulation::set_joint_damping(const JointVector& damping_nms_per_rad) {
  mjModel* m = sim_.model();
  for (size_t i = 0; i < joints_.count; ++i) {
    m->dof_damping[joints_.dof[i]] = model_damping_[i] + damping_nms_per_rad[i];
  }
}

void TwinSimulation::step_coupled(const JointVector& q_coupled_rad) {
  const double k = config_.coupling_stiffness_nm_per_rad;
  const double c = config_.coupling_damping_nms_per_rad;
  // eq. 2's damping term as joint damping, which MuJoCo's Euler integrator treats implicitly:
  // stable for stiff couplings on light wrist links where an explicit -D dq is not
  JointVector damping;
  damping.fill(c);
  set_joint_damping(damping);
  advance([&](size_t i, double q, double) { return k * (q_coupled_rad[i] - q); });
  for (size_t i = 0; i < joints_.count; ++i) tau_[i] -= c * dq_[i];
}

void TwinSimulation::step_torque(const JointVector& tau_nm) { step_torque(tau_nm, JointVector{}); }

void TwinSimulation::step_torque(const JointVector& tau_nm, const JointVector& damping_nms_per_rad) {
  set_joint_damping(damping_nms_per_rad);
  advance([&](size_t i, double, double) { return tau_nm[i]; });
  for (size_t i = 0; i < joints_.count; ++i) tau_[i] -= damping_nms_per_rad[i] * dq_[i];
}

void TwinSimulation::set_state(const JointVector& q_rad, const JointVector& dq_radps) {
  mjData* d = sim_.data();
  for (size_t i = 0; i < joints_.count; ++i) {
    d->qpos[joints_.qpos[i]] = q_rad[i];
    d->qvel[joints_.dof[i]] = dq_radps[i];
  }
  mj_forward(sim_.model(), d);
  read_back();
}

void TwinSimulation::read_back() {
  const mjModel* m = sim_.model();
  mjData* d = sim_.data();
  const mjtNum* rendered = d->qfrc_constraint;
  if (!config_.render_joint_friction) {
    // J^T f over the contact and limit rows only: dry joint friction is the twin's own business
    for (int r = 0; r < d->nefc; ++r) {
      const bool friction = d->efc_type[r] == mjCNSTR_FRICTION_DOF || d->efc_type[r] == mjCNSTR_FRICTION_TENDON;
      efc_rendered_[static_cast<size_t>(r)] = friction ? 0.0 : d->efc_force[r];
    }
    mj_mulJacTVec(m, d, qfrc_rendered_.data(), efc_rendered_.data());
    rendered = qfrc_rendered_.data();
  }
  for (size_t i = 0; i < joints_.count; ++i) {
    q_[i] = d->qpos[joints_.qpos[i]];
    dq_[i] = d->qvel[joints_.dof[i]];
    constraint_[i] = rendered[joints_.dof[i]];
  }
}

}  // namespace teleop::twin
