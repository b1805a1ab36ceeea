#pragma once
// Probes: observers of a simulated world that a node runs once per control cycle after the world
// stepped, beside its arms: an experiment's (the box task's records the box, the hands and the
// squeeze into the node's trace). A probe library registers its probes by name in linked_probes()
// when it is linked into an executable (teleop_follower links the box task's whole, in CMake: the
// node's code names no probe); a node's configuration asks for them (`node.probes: [box_task]`,
// set by the experiment, never a key of the robot's own section). Setup time only.

#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "teleop/robot/mujoco_scene.h"
#include "teleop/runtime/node_logic.h"

namespace teleop::robot {

class SceneProbes {
 public:
  /// Builds the probe on `scene`; throws naming what the scene lacks.
  using Factory = std::function<std::unique_ptr<runtime::NodeLogic>(std::shared_ptr<const MujocoScene> scene)>;

  void add(std::string name, Factory factory);
  bool has(const std::string& name) const;
  std::unique_ptr<runtime::NodeLogic> make(const std::string& name, std::shared_ptr<const MujocoScene> scene) const;
  /// The names, comma-separated, for messages.
  std::string names() const;

 private:
  std::vector<std::pair<std::string, Factory>> factories_;
};

/// The probes of the libraries linked into this executable.
SceneProbes& linked_probes();

}  // namespace teleop::robot
