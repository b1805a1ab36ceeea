#include "teleop/sim/model_config.h"

#include <stdexcept>

#include "teleop/sim/mujoco_model.h"

namespace teleop::sim {

std::string get_model_path(const ConfigNode& section, const std::string& key) {
  const std::string path = section.get_path(key);
  try {
    (void)MujocoModel::load(path);
  } catch (const std::runtime_error& e) {
    throw section.error(key, std::string("the model does not load: ") + e.what());
  }
  return path;
}

}  // namespace teleop::sim
