#include "teleop/view/posed_scene.h"

#include <algorithm>
#include <stdexcept>

namespace teleop::view {

const char* layer_name(Layer layer) {
  switch (layer) {
    case Layer::kFollower:
      return "follower";
    case Layer::kTwin:
      return "twin";
    case Layer::kLeader:
      return "leader";
  }
  return "?";
}

namespace {

// joints posed by name (the hand's coupled joints have no actuator): hinge or slide joints, in the
// order of `names`
sim::ActuatedJoints named_joints(const mjModel* m, const std::string& model_name, const std::vector<std::string>& names) {
  if (names.size() > sim::kMaxActuatedJoints) {
    throw std::runtime_error("MuJoCo model '" + model_name + "': more than " +
                             std::to_string(sim::kMaxActuatedJoints) + " joints to pose");
  }
  sim::ActuatedJoints joints;
  for (const std::string& name : names) {
    const int j = mj_name2id(m, mjOBJ_JOINT, name.c_str());
    if (j < 0 || (m->jnt_type[j] != mjJNT_HINGE && m->jnt_type[j] != mjJNT_SLIDE)) {
      throw std::runtime_error("MuJoCo model '" + model_name + "' has no hinge or slide joint '" + name + "'");
    }
    joints.qpos[joints.count] = m->jnt_qposadr[j];
    joints.dof[joints.count] = m->jnt_dofadr[j];
    joints.actuator[joints.count] = -1;
    ++joints.count;
  }
  return joints;
}

}  // namespace

PosedScene::PosedScene(const ViewModelSpec& spec) : spec_(spec), sim_(sim::MujocoModel::load(spec.model_path)) {
  const mjModel* m = sim_.model();
  if (!spec_.keyframe.empty()) keyframe_ = sim_.keyframe_id(spec_.keyframe);
  moved_by_arms_.assign(static_cast<size_t>(m->nbody), false);
  for (const ViewArm& arm : spec_.arms) {
    joints_.push_back(arm.joint_names.empty() ? sim::find_actuated_joints(m, spec_.model_path, arm.joint_prefix)
                                              : named_joints(m, spec_.model_path, arm.joint_names));
    const std::string site = arm.ee_site.empty() ? arm.joint_prefix + "ee_site" : arm.ee_site;
    ee_sites_.push_back(mj_name2id(m, mjOBJ_SITE, site.c_str()));
    const sim::ActuatedJoints& j = joints_.back();
    for (size_t i = 0; i < j.count; ++i) {
      moved_by_arms_[static_cast<size_t>(m->jnt_bodyid[m->dof_jntid[j.dof[i]]])] = true;
    }
  }
  // bodies are numbered parents first: a body is moved when its parent is
  for (int b = 1; b < m->nbody; ++b) {
    if (moved_by_arms_[static_cast<size_t>(m->body_parentid[b])]) moved_by_arms_[static_cast<size_t>(b)] = true;
  }
  for (int j = 0; j < m->njnt; ++j) {
    if (m->jnt_type[j] != mjJNT_FREE) continue;
    const char* name = mj_id2name(m, mjOBJ_BODY, m->jnt_bodyid[j]);
    free_bodies_.push_back({name != nullptr ? name : "", m->jnt_bodyid[j], m->jnt_qposadr[j], m->jnt_dofadr[j]});
  }
  for (size_t l = 0; l < kLayerCount; ++l) {
    data_[l] = mj_makeData(m);
    if (data_[l] == nullptr) throw std::runtime_error("cannot make MuJoCo data for model '" + spec_.model_path + "'");
    reset_layer(l);
  }
}

PosedScene::~PosedScene() {
  for (mjData* d : data_) mj_deleteData(d);
}

void PosedScene::reset_layer(size_t layer) {
  const mjModel* m = sim_.model();
  if (keyframe_ >= 0) {
    mj_resetDataKeyframe(m, data_[layer], keyframe_);
  } else {
    mj_resetData(m, data_[layer]);
  }
  mj_forward(m, data_[layer]);
  posed_[layer] = false;
}

void PosedScene::clear(Layer layer) { reset_layer(index(layer)); }

bool PosedScene::set_joints(Layer layer, size_t arm, const double* q, size_t n, const double* dq, const double* tau) {
  const sim::ActuatedJoints& j = joints_.at(arm);
  if (n != j.count) return false;
  mjData* d = data_[index(layer)];
  for (size_t i = 0; i < n; ++i) {
    d->qpos[j.qpos[i]] = q[i];
    d->qvel[j.dof[i]] = dq != nullptr ? dq[i] : 0.0;
    d->qfrc_applied[j.dof[i]] = tau != nullptr ? tau[i] : 0.0;
  }
  posed_[index(layer)] = true;
  return true;
}

void PosedScene::set_body_pose(Layer layer, size_t free_body, const double* position, const double* quaternion) {
  const FreeBody& b = free_bodies_.at(free_body);
  mjData* d = data_[index(layer)];
  std::copy_n(position, 3, d->qpos + b.qpos);
  std::copy_n(quaternion, 4, d->qpos + b.qpos + 3);
  mju_normalize4(d->qpos + b.qpos + 3);
  std::fill_n(d->qvel + b.dof, 6, 0.0);
}

void PosedScene::update() {
  const mjModel* m = sim_.model();
  // the follower: its contacts and their forces under the measured torques, as its own simulation
  // computes them (the viewer never steps: the pose stays the measured one)
  if (posed_[index(Layer::kFollower)]) mj_forward(m, data_[index(Layer::kFollower)]);
  for (Layer ghost : {Layer::kTwin, Layer::kLeader}) {
    if (posed_[index(ghost)]) mj_kinematics(m, data_[index(ghost)]);
  }
}

}  // namespace teleop::view
