#pragma once
// Loading a model with extra MJCF elements that only one simulation sees (e.g. the twin's
// safety-margin geometry, PARTI §3.1), without editing the model files: the model is loaded once,
// flattened by MuJoCo (mj_saveLastXML resolves every include), the elements are inserted into the
// flat text and the result is compiled.

#include <string>
#include <vector>

#include "teleop/sim/mujoco_model.h"

namespace teleop::sim {

/// One MJCF element (e.g. `<geom type="sphere" .../>`) inserted as the first child of `body`
/// (empty: the worldbody).
struct ModelAddition {
  std::string body;
  std::string element_xml;
};

/// Loads `path` with `additions`. Throws std::runtime_error naming `path` when the model does not
/// load, a body does not exist, or the result does not compile (carrying MuJoCo's error text).
/// Setup time: allocates, writes two scratch files under the temp directory and removes them.
MujocoModel load_with_additions(const std::string& path, const std::vector<ModelAddition>& additions);

/// The flat MJCF text of `path` with `additions` inserted (what load_with_additions compiles).
std::string flatten_with_additions(const std::string& path, const std::vector<ModelAddition>& additions);

}  // namespace teleop::sim
