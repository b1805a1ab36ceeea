// PARTI §3.2: the taught trajectory on the "real" robot, its lock-step replay on the twin, the
// estimators on the real robot's measurements.
#include "teleop/experiment/parti_twin_study.h"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <stdexcept>

#include "fidelity_arm.h"
#include "teleop/control/arm_dynamics.h"
#include "teleop/control/estimators.h"
#include "teleop/control/min_jerk.h"

namespace teleop::experiment {
namespace {

// a contact force below this is numerical chatter, not a touch [N]
constexpr double kTouchN = 0.5;

FidelityStudyConfig arm_config(const PartiTwinConfig& c) {
  FidelityStudyConfig f;
  f.name = c.name;
  f.file = c.file;
  f.ee_site = c.ee_site;
  f.cartesian_impedance = c.gains;
  f.perturbation = c.perturbation;
  f.sensor_noise = c.sensor_noise;
  return f;
}

control::JointVector keyframe_q(const sim::MujocoModel& model, const std::string& key) {
  const mjModel* m = model.model();
  const int k = mj_name2id(m, mjOBJ_KEY, key.c_str());
  if (k < 0) throw std::runtime_error(model.path() + ": no keyframe '" + key + "'");
  control::JointVector q;
  for (int i = 0; i < control::kDof; ++i) q[i] = m->key_qpos[k * m->nq + i];
  return q;
}

// the taught trajectory as commands, one per 1 ms step: minimum-jerk moves between the waypoints,
// the start's orientation and the start pose as the nullspace rest
std::vector<control::ArmCommand> taught_commands(const PartiTwinConfig& c, const control::JointVector& q0, double dt) {
  sim::MujocoModel nominal = sim::MujocoModel::load(c.model_path);
  control::ArmDynamics dyn(nominal.model(), c.ee_site);
  dyn.update(control::ArmState{q0, control::JointVector::Zero()});
  const Eigen::Vector3d p0 = dyn.ee_position();
  control::MinJerkPath path({p0.x(), p0.y(), p0.z()});
  double duration_s = c.start_hold_s;
  path.then({p0.x(), p0.y(), p0.z()}, c.start_hold_s);
  for (const PartiWaypoint& w : c.waypoints) {
    const std::vector<double> p{w.position_m.x(), w.position_m.y(), w.position_m.z()};
    path.then(p, w.move_s);
    duration_s += w.move_s;
    if (w.hold_s > 0) {
      path.then(p, w.hold_s);
      duration_s += w.hold_s;
    }
  }
  control::ArmCommand base;
  base.orientation_d = Eigen::Quaterniond(dyn.ee_rotation());
  base.q_rest = q0;
  std::vector<control::ArmCommand> out(static_cast<size_t>(std::lround(duration_s / dt)), base);
  std::array<double, 3> x{};
  std::array<double, 3> v{};
  for (size_t k = 0; k < out.size(); ++k) {
    path.sample(static_cast<double>(k) * dt, x, v);
    out[k].x_d = Eigen::Vector3d(x[0], x[1], x[2]);
    out[k].twist_d.head<3>() = Eigen::Vector3d(v[0], v[1], v[2]);
  }
  return out;
}

// the contacts' force on the robot and its moment about the end effector, world frame (force on
// geom2 along the contact normal, which points from geom1 to geom2)
control::Vector6 contact_wrench(const mjModel* m, const mjData* d, int site) {
  control::Vector6 w = control::Vector6::Zero();
  const Eigen::Vector3d p_site(d->site_xpos[3 * site], d->site_xpos[3 * site + 1], d->site_xpos[3 * site + 2]);
  for (int i = 0; i < d->ncon; ++i) {
    const mjContact& c = d->contact[i];
    const bool robot1 = m->geom_bodyid[c.geom1] != 0;
    const bool robot2 = m->geom_bodyid[c.geom2] != 0;
    if (robot1 == robot2) continue;  // the world against itself, or the arm against itself
    mjtNum f[6];
    mj_contactForce(m, d, i, f);
    Eigen::Vector3d force = Eigen::Vector3d::Zero();
    for (int r = 0; r < 3; ++r) force += f[r] * Eigen::Vector3d(c.frame[3 * r], c.frame[3 * r + 1], c.frame[3 * r + 2]);
    if (!robot2) force = -force;
    const Eigen::Vector3d at(c.pos[0], c.pos[1], c.pos[2]);
    w.head<3>() += force;
    w.tail<3>() += (at - p_site).cross(force);
  }
  return w;
}

double angle_between(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  return 2.0 * std::acos(std::min(1.0, std::abs(a.dot(b))));
}

// what one arm did at every step
struct ArmRecord {
  std::vector<Eigen::Vector3d> position;
  std::vector<Eigen::Quaterniond> rotation;
  std::vector<control::Vector6> wrench;  // true contact wrench
  std::vector<double> speed_mps;         // the end effector's true speed
  int warnings = 0;
};

// The estimators on the real robot's measurements, with the nominal model.
class Estimators {
 public:
  Estimators(const PartiTwinConfig& c, double dt)
      : model_(sim::MujocoModel::load(c.model_path)),
        dyn_observer_(model_.model(), c.ee_site),
        dyn_link_(model_.model(), c.ee_site),
        dyn_command_(model_.model(), c.ee_site),
        dyn_direct_(model_.model(), c.ee_site),
        dyn_gravity_(model_.model(), c.ee_site),
        observer_(dyn_observer_, dt, control::JointVector::Constant(c.observer_gain_per_s)),
        link_(dyn_link_, c.direct_gamma),
        command_(dyn_command_, c.direct_gamma),
        direct_(dyn_direct_, dt, c.direct_gamma) {}

  // the measurement after a step, the link torque of that step and the control law's torque
  void update(const control::ArmState& s, const control::JointVector& tau_j, const control::JointVector& tau_cmd) {
    observer_.update(s, tau_j);
    link_.update(s.q, control::JointVector::Zero(), tau_j);
    dyn_gravity_.update(control::ArmState{s.q, control::JointVector::Zero()});
    command_.update(s.q, tau_cmd - dyn_gravity_.gravity(), tau_j);
    direct_.update(s, tau_j);
  }
  // the estimate's force at the end effector (eq. 8 through the pseudo-inverse)
  Eigen::Vector3d force(int estimator) const {
    switch (estimator) {
      case kObserver: return control::wrench_from_torque(dyn_observer_, observer_.external_torque()).head<3>();
      case kPartiLink: return control::wrench_from_torque(dyn_link_, link_.external_torque()).head<3>();
      case kPartiCommand: return control::wrench_from_torque(dyn_command_, command_.external_torque()).head<3>();
      default: return control::wrench_from_torque(dyn_direct_, direct_.external_torque()).head<3>();
    }
  }

 private:
  sim::MujocoModel model_;
  control::ArmDynamics dyn_observer_;
  control::ArmDynamics dyn_link_;
  control::ArmDynamics dyn_command_;
  control::ArmDynamics dyn_direct_;
  control::ArmDynamics dyn_gravity_;
  control::MomentumObserver observer_;
  control::PartiDirectEstimator link_;
  control::PartiDirectEstimator command_;
  control::DirectEstimator direct_;
};

// drives `arm` through `commands`, recording what the arm reports; `each(arm)` after every step
template <typename Each>
ArmRecord drive(FidelityArm& arm, const PartiTwinConfig& c, const control::JointVector& q0,
                const std::vector<control::ArmCommand>& commands, Each&& each) {
  ArmRecord r;
  ForwardKinematics fk(c.model_path, c.ee_site);
  const mjModel* m = arm.plant().model();
  const mjData* d = arm.plant().data();
  const int site = arm.plant().site_id(c.ee_site);
  arm.place(q0);
  Eigen::Vector3d last(d->site_xpos[3 * site], d->site_xpos[3 * site + 1], d->site_xpos[3 * site + 2]);
  const double dt = arm.timestep_s();
  std::array<double, 3> p{};
  Quaternion q{};
  for (const control::ArmCommand& command : commands) {
    arm.step(command);
    each(arm);
    fk.pose(arm.measured().q, p, q);
    r.position.emplace_back(p[0], p[1], p[2]);
    r.rotation.emplace_back(q[0], q[1], q[2], q[3]);
    r.wrench.push_back(contact_wrench(m, d, site));
    const Eigen::Vector3d now(d->site_xpos[3 * site], d->site_xpos[3 * site + 1], d->site_xpos[3 * site + 2]);
    r.speed_mps.push_back((now - last).norm() / dt);
    last = now;
  }
  r.warnings = arm.mujoco_warnings();
  return r;
}

void add(PhaseError& e, double v) {
  e.mean += v;
  e.max = std::max(e.max, v);
  ++e.samples;
}

void finish(PhaseError& e) { e.mean = e.samples > 0 ? e.mean / static_cast<double>(e.samples) : std::nan(""); }

}  // namespace

const char* estimator_name(int estimator) {
  constexpr const char* kNames[] = {"observer", "parti_link", "parti_command", "direct_inertial"};
  return estimator >= 0 && estimator < kEstimatorCount ? kNames[estimator] : "?";
}

const char* phase_name(int phase) {
  constexpr const char* kNames[] = {"free", "contact", "static_contact"};
  return phase >= 0 && phase < kPhaseCount ? kNames[phase] : "?";
}

PartiTwinRun run_parti_twin_case(const PartiTwinConfig& c, uint64_t seed) {
  const FidelityStudyConfig fc = arm_config(c);
  FidelityArm real(fc, c.model_path, FidelityController::kCartesianImpedance, seed);
  FidelityArm twin(fc, c.model_path, FidelityController::kCartesianImpedance, std::nullopt);
  const control::JointVector q0 = keyframe_q(real.plant(), c.keyframe);
  const double dt = real.timestep_s();
  const std::vector<control::ArmCommand> commands = taught_commands(c, q0, dt);

  PartiTwinRun run;
  run.seed = seed;
  Estimators estimators(c, dt);
  std::vector<std::array<Eigen::Vector3d, kEstimatorCount>> estimates;
  estimates.reserve(commands.size());
  const ArmRecord r = drive(real, c, q0, commands, [&](const FidelityArm& arm) {
    estimators.update(arm.measured(), arm.tau_measured(), arm.tau_commanded());
    std::array<Eigen::Vector3d, kEstimatorCount> e;
    for (int i = 0; i < kEstimatorCount; ++i) e[static_cast<size_t>(i)] = estimators.force(i);
    estimates.push_back(e);
  });
  const ArmRecord t = drive(twin, c, q0, commands, [](const FidelityArm&) {});
  run.mujoco_warnings = r.warnings + t.warnings;

  // the estimators start from zero and the arm settles on its controller: evaluate after that
  const double settle_s = 0.5 * c.start_hold_s;
  for (size_t k = 0; k < commands.size(); ++k) {
    const double time = static_cast<double>(k + 1) * dt;
    const Eigen::Vector3d f_real = r.wrench[k].head<3>();
    const bool touching = f_real.norm() > kTouchN;
    const int phase = !touching ? kFree : (r.speed_mps[k] < c.static_speed_mps ? kStaticContact : kContact);
    run.t_s.push_back(time);
    run.phase.push_back(phase);
    run.position_mm.push_back(1000.0 * (r.position[k] - t.position[k]).norm());
    run.rotation_mrad.push_back(1000.0 * angle_between(r.rotation[k], t.rotation[k]));
    run.force_error_n.push_back((f_real - t.wrench[k].head<3>()).norm());
    run.moment_error_nm.push_back((r.wrench[k].tail<3>() - t.wrench[k].tail<3>()).norm());
    run.f_true_z_n.push_back(f_real.z());
    run.f_twin_z_n.push_back(t.wrench[k].z());
    run.peak_force_n = std::max(run.peak_force_n, f_real.norm());
    for (int i = 0; i < kEstimatorCount; ++i) {
      const Eigen::Vector3d& e = estimates[k][static_cast<size_t>(i)];
      run.f_estimate_z_n[i].push_back(e.z());
      run.estimate_error_n[i].push_back((e - f_real).norm());
    }
    if (time < settle_s) continue;
    // static contact is contact too
    if (phase == kStaticContact) run.static_force_n += f_real.norm();
    for (const int p : {phase, phase == kStaticContact ? static_cast<int>(kContact) : -1}) {
      if (p < 0) continue;
      add(run.position[p], run.position_mm.back());
      add(run.force[p], run.force_error_n.back());
      for (int i = 0; i < kEstimatorCount; ++i) add(run.estimator[i][p], run.estimate_error_n[i].back());
    }
  }
  const size_t n_static = run.position[kStaticContact].samples;
  run.static_force_n = n_static > 0 ? run.static_force_n / static_cast<double>(n_static) : std::nan("");
  for (int p = 0; p < kPhaseCount; ++p) {
    finish(run.position[p]);
    finish(run.force[p]);
    for (int i = 0; i < kEstimatorCount; ++i) finish(run.estimator[i][p]);
  }
  return run;
}

}  // namespace teleop::experiment
