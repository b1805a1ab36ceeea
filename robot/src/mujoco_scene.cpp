#include "teleop/robot/mujoco_scene.h"

#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "simulated_payload.h"
#include "teleop/sim/model_additions.h"

namespace teleop::robot {
namespace {

void delete_data(mjData* d) { mj_deleteData(d); }
void delete_model(mjModel* m) { mj_deleteModel(m); }

// the scene, with the payload's body under the site's body when there is one
sim::MujocoModel load_scene(const MujocoSceneConfig& config) {
  if (!config.payload) return sim::MujocoModel::load(config.model_path);
  const sim::MujocoModel base = sim::MujocoModel::load(config.model_path);
  return sim::load_with_additions(config.model_path, {payload_addition(base.model(), config.model_path, *config.payload)});
}

}  // namespace

MujocoScene::MujocoScene(const MujocoSceneConfig& config)
    : sim_(load_scene(config)),
      nominal_(nullptr, delete_model),
      rest_(nullptr, delete_data),
      real_robot_(config.real_robot),
      file_name_(std::filesystem::path(config.model_path).filename().string()) {
  if (config.payload) {
    // the robot compensates the gravity of the arm it was told about, without the tool
    nominal_.reset(mj_copyModel(nullptr, sim::MujocoModel::load(config.model_path).model()));
  } else if (real_robot_) {
    nominal_.reset(mj_copyModel(nullptr, sim_.model()));
  }
  if ((config.payload || real_robot_) && !nominal_) throw std::runtime_error(config.model_path + ": cannot copy the model");
  if (real_robot_) {
    // every arm of the scene off by its own draw; gravity compensation from the model as it was
    const sim::ActuatedJoints joints = sim::find_actuated_joints(sim_.model(), config.model_path);
    perturbation_ = sim::perturb_plant(sim_.model(), sim_.data(), joints, real_robot_->perturbation,
                                       sim::derived_seed(real_robot_->seed, 0));
    perturbation_.seed = real_robot_->seed;
    sim_.reset();
  }
  const mjModel* m = sim_.model();
  if (!config.keyframe.empty()) sim_.reset(config.keyframe);
  rest_.reset(mj_makeData(nominal_ ? nominal_.get() : m));
  const double steps = config.period_s / m->opt.timestep;
  substeps_ = static_cast<int>(std::lround(steps));
  if (substeps_ < 1 || std::abs(steps - substeps_) > 1e-6) {
    throw std::runtime_error(config.model_path + ": timestep " + std::to_string(m->opt.timestep) +
                             " s does not divide the control period " + std::to_string(config.period_s) + " s");
  }
  mj_forward(m, sim_.data());
}

void MujocoScene::step() {
  for (int s = 0; s < substeps_; ++s) mj_step(sim_.model(), sim_.data());
  gravity_current_ = false;
}

void MujocoScene::state_changed() {
  mj_forward(sim_.model(), sim_.data());
  gravity_current_ = false;
}

const mjtNum* MujocoScene::gravity() {
  if (!gravity_current_) {
    const mjModel* m = nominal_ ? nominal_.get() : sim_.model();
    // the same pose at rest: the bias forces are then gravity alone
    mju_copy(rest_->qpos, sim_.data()->qpos, m->nq);
    mju_zero(rest_->qvel, m->nv);
    mj_kinematics(m, rest_.get());
    mj_comPos(m, rest_.get());
    mj_rne(m, rest_.get(), 0, rest_->qfrc_bias);
    gravity_current_ = true;
  }
  return rest_->qfrc_bias;
}

}  // namespace teleop::robot
