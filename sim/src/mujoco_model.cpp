#include "teleop/sim/mujoco_model.h"

#include <array>
#include <mutex>
#include <stdexcept>
#include <utility>

#include "xml_mutex.h"

namespace teleop::sim {

namespace {

// MuJoCo's messages span several lines: join them into one, trimmed.
std::string one_line(const char* text) {
  std::string out;
  for (const char* c = text; *c != '\0'; ++c) {
    const bool space = *c == '\n' || *c == '\r' || *c == '\t' || *c == ' ';
    if (!space) {
      out += *c;
    } else if (!out.empty() && out.back() != ' ') {
      out += ' ';
    }
  }
  while (!out.empty() && out.back() == ' ') out.pop_back();
  return out;
}

}  // namespace

std::mutex& xml_mutex() {
  static std::mutex m;
  return m;
}

MujocoModel MujocoModel::load(const std::string& path) {
  std::array<char, 1024> error{};
  std::unique_ptr<mjModel, ModelDeleter> model;
  {
    const std::lock_guard lock(xml_mutex());
    model.reset(mj_loadXML(path.c_str(), nullptr, error.data(), static_cast<int>(error.size())));
  }
  error.back() = '\0';
  if (!model) {
    const std::string text = one_line(error.data());
    throw std::runtime_error("cannot load MuJoCo model '" + path + "': " + (text.empty() ? "unknown error" : text));
  }
  std::unique_ptr<mjData, DataDeleter> data(mj_makeData(model.get()));
  if (!data) {
    throw std::runtime_error("cannot make MuJoCo data for model '" + path + "'");
  }
  MujocoModel result(path, std::move(model), std::move(data), one_line(error.data()));
  mj_forward(result.model(), result.data());
  return result;
}

MujocoModel::MujocoModel(std::string path, std::unique_ptr<mjModel, ModelDeleter> model,
                         std::unique_ptr<mjData, DataDeleter> data, std::string warning)
    : path_(std::move(path)), model_(std::move(model)), data_(std::move(data)), warning_(std::move(warning)) {}

int MujocoModel::id_of(mjtObj type, const char* kind, std::string_view name) const {
  const std::string key(name);
  const int id = mj_name2id(model_.get(), type, key.c_str());
  if (id < 0) {
    throw std::out_of_range("MuJoCo model '" + path_ + "' has no " + kind + " named '" + key + "'");
  }
  return id;
}

int MujocoModel::joint_id(std::string_view name) const { return id_of(mjOBJ_JOINT, "joint", name); }
int MujocoModel::site_id(std::string_view name) const { return id_of(mjOBJ_SITE, "site", name); }
int MujocoModel::actuator_id(std::string_view name) const { return id_of(mjOBJ_ACTUATOR, "actuator", name); }
int MujocoModel::body_id(std::string_view name) const { return id_of(mjOBJ_BODY, "body", name); }
int MujocoModel::geom_id(std::string_view name) const { return id_of(mjOBJ_GEOM, "geom", name); }
int MujocoModel::keyframe_id(std::string_view name) const { return id_of(mjOBJ_KEY, "keyframe", name); }

int MujocoModel::joint_qpos_address(std::string_view name) const { return model_->jnt_qposadr[joint_id(name)]; }
int MujocoModel::joint_dof_address(std::string_view name) const { return model_->jnt_dofadr[joint_id(name)]; }

void MujocoModel::reset() {
  mj_resetData(model_.get(), data_.get());
  mj_forward(model_.get(), data_.get());
}

void MujocoModel::reset(std::string_view keyframe) {
  const int key = keyframe_id(keyframe);
  mj_resetDataKeyframe(model_.get(), data_.get(), key);
  mj_forward(model_.get(), data_.get());
}

}  // namespace teleop::sim
