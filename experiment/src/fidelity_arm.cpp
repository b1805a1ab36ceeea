#include "fidelity_arm.h"

#include <stdexcept>

namespace teleop::experiment {
namespace {

// the robot's own stream and its sensors' stream of one seed
constexpr uint64_t kRobotStream = 0;
constexpr uint64_t kSensorStream = 1;

sim::ActuatedJoints arm_joints(const sim::MujocoModel& model) {
  const sim::ActuatedJoints joints = sim::find_actuated_joints(model.model(), model.path());
  if (joints.count != static_cast<size_t>(control::kDof)) {
    throw std::runtime_error(model.path() + ": the fidelity study needs exactly " + std::to_string(control::kDof) +
                             " actuated arm joints, the model has " + std::to_string(joints.count));
  }
  return joints;
}

std::unique_ptr<control::Controller> make_controller(const FidelityStudyConfig& c, FidelityController kind,
                                                     control::ArmDynamics& dynamics) {
  if (kind == FidelityController::kStateSpace) return std::make_unique<control::PositionPd>(c.state_space);
  if (kind == FidelityController::kCartesianImpedance) {
    return std::make_unique<control::CartesianImpedance>(dynamics, c.cartesian_impedance);
  }
  return std::make_unique<control::JointImpedance>(dynamics, c.joint_impedance);
}

}  // namespace

FidelityArm::FidelityArm(const FidelityStudyConfig& config, const std::string& model_path,
                         FidelityController controller, std::optional<uint64_t> real_seed)
    : plant_(sim::MujocoModel::load(model_path)),
      nominal_(sim::MujocoModel::load(model_path)),
      joints_(arm_joints(plant_)),
      dynamics_(nominal_.model(), config.ee_site),
      controller_(make_controller(config, controller, dynamics_)) {
  mjModel* m = plant_.model();
  if (real_seed) {
    perturbation_ =
        sim::perturb_plant(m, plant_.data(), joints_, config.perturbation, sim::derived_seed(*real_seed, kRobotStream));
    perturbation_.seed = *real_seed;
    noise_.emplace(config.sensor_noise, sim::derived_seed(*real_seed, kSensorStream));
  }
  joint_of_dof_.assign(static_cast<size_t>(m->nv), -1);
  for (size_t i = 0; i < joints_.count; ++i) joint_of_dof_[static_cast<size_t>(joints_.dof[i])] = static_cast<int>(i);
  mj_resetData(m, plant_.data());
}

void FidelityArm::place(const control::JointVector& q_rad) {
  const mjModel* m = plant_.model();
  mjData* d = plant_.data();
  mj_resetData(m, d);
  for (size_t i = 0; i < joints_.count; ++i) d->qpos[joints_.qpos[i]] = q_rad[static_cast<int>(i)];
  mj_forward(m, d);
  tau_.setZero();
  measure();
}

void FidelityArm::step(const RecordedCommand& command) {
  command_.q_d = command.q_d;
  command_.dq_d = command.dq_d;
  step(command_);
}

void FidelityArm::step(const control::ArmCommand& command) {
  tau_commanded_ = controller_->compute(measured_, command);
  const control::JointVector& tau = tau_commanded_;
  const mjModel* m = plant_.model();
  mjData* d = plant_.data();
  for (size_t i = 0; i < joints_.count; ++i) d->ctrl[joints_.actuator[i]] = tau[static_cast<int>(i)];
  mj_step(m, d);
  // the link-side torque of this step: the motor's (after its limit), the joint's damping and its
  // dry friction (the friction rows of the constraint forces); forces of this step, before the
  // integration moved the state on
  for (size_t i = 0; i < joints_.count; ++i) {
    tau_[static_cast<int>(i)] = d->actuator_force[joints_.actuator[i]] + d->qfrc_passive[joints_.dof[i]];
  }
  for (int r = 0; r < d->nefc; ++r) {
    if (d->efc_type[r] != mjCNSTR_FRICTION_DOF) continue;
    const int joint = joint_of_dof_[static_cast<size_t>(d->efc_id[r])];
    if (joint >= 0) tau_[joint] += d->efc_force[r];
  }
  measure();
}

void FidelityArm::measure() {
  const mjData* d = plant_.data();
  for (size_t i = 0; i < joints_.count; ++i) {
    const int k = static_cast<int>(i);
    measured_.q[k] = d->qpos[joints_.qpos[i]];
    measured_.dq[k] = d->qvel[joints_.dof[i]];
  }
  if (!noise_) return;
  for (int k = 0; k < control::kDof; ++k) {
    measured_.q[k] += noise_->q_rad();
    measured_.dq[k] += noise_->dq_radps();
    tau_[k] += noise_->tau_nm();
  }
}

int FidelityArm::mujoco_warnings() const {
  int n = 0;
  for (const mjWarningStat& w : plant_.data()->warning) n += w.number;
  return n;
}

ForwardKinematics::ForwardKinematics(const std::string& model_path, const std::string& ee_site)
    : model_(sim::MujocoModel::load(model_path)), joints_(arm_joints(model_)), site_(model_.site_id(ee_site)) {}

void ForwardKinematics::pose(const control::JointVector& q_rad, std::array<double, 3>& position_m,
                             Quaternion& rotation) {
  const mjModel* m = model_.model();
  mjData* d = model_.data();
  for (size_t i = 0; i < joints_.count; ++i) d->qpos[joints_.qpos[i]] = q_rad[static_cast<int>(i)];
  mj_kinematics(m, d);
  for (int k = 0; k < 3; ++k) position_m[static_cast<size_t>(k)] = d->site_xpos[3 * site_ + k];
  mju_mat2Quat(rotation.data(), d->site_xmat + 9 * site_);
}

}  // namespace teleop::experiment
