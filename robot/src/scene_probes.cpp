#include "teleop/robot/scene_probes.h"

#include <stdexcept>

namespace teleop::robot {

void SceneProbes::add(std::string name, Factory factory) {
  if (has(name)) throw std::logic_error("probe " + name + " registered twice");
  factories_.emplace_back(std::move(name), std::move(factory));
}

bool SceneProbes::has(const std::string& name) const {
  for (const auto& [known, factory] : factories_) {
    if (known == name) return true;
  }
  return false;
}

std::unique_ptr<runtime::NodeLogic> SceneProbes::make(const std::string& name,
                                                      std::shared_ptr<const MujocoScene> scene) const {
  for (const auto& [known, factory] : factories_) {
    if (known == name) return factory(std::move(scene));
  }
  throw std::invalid_argument("no probe " + name + " (this executable has: " + names() + ")");
}

std::string SceneProbes::names() const {
  std::string out;
  for (const auto& [name, factory] : factories_) out += (out.empty() ? "" : ", ") + name;
  return out.empty() ? "none" : out;
}

SceneProbes& linked_probes() {
  static SceneProbes probes;
  return probes;
}

}  // namespace teleop::robot
