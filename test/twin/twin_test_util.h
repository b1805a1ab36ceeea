#pragma once
// Helpers shared by the twin's tests.

#include <mujoco/mujoco.h>

#include <cmath>
#include <string>

#include "teleop/common/config.h"
#include "teleop/twin/twin_model_config.h"

namespace teleop::twin::test {

/// The message of the ConfigError `parse` throws for the config text `yaml` read as the file
/// `file_name`; "" when it throws none.
template <typename Parse>
std::string config_error(Parse parse, const std::string& yaml, const std::string& file_name) {
  try {
    parse(ConfigNode::load_string(yaml, file_name));
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

inline std::string model_path(const std::string& name) {
  return std::string(TELEOP_SOURCE_DIR) + "/config/models/" + name;
}

/// The Panda arm 5 cm in front of the wall of scene_wall.xml, coupled as in config/nodes/twin.yaml.
inline TwinModelConfig wall_model() {
  TwinModelConfig c;
  c.model_path = model_path("scene_wall.xml");
  c.keyframe = "facing_wall";
  c.contact_pairs = {{"flange_wall", "body:link7", "geom:wall"}};
  c.distance_pairs = {{"flange_wall", "geom:link7_flange", "geom:wall"}};
  return c;
}

/// Joint 2 (index 1, the shoulder) moves the flange towards the wall (+x) when it grows.
inline constexpr size_t kShoulder = 1;

inline double distance(const mjtNum* a, const mjtNum* b) {
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

}  // namespace teleop::twin::test
