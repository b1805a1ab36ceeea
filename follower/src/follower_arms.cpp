#include "follower_arms.h"

#include <memory>

#include "teleop/follower/follower_node.h"
#include "object_pose_feed.h"
#include "teleop/robot/mujoco_backend.h"
#include "teleop/robot/mujoco_hardware.h"
#include "teleop/runtime/arm_group.h"

namespace teleop::follower {
namespace {

// what a follower process is built from, read before it joins the network
struct FollowerSetup {
  std::vector<FollowerConfig> arms;
  std::vector<std::string> probes;
  /// Its world is observed (probes, tracked objects) or shared by several arms: one scene for all.
  bool shared_scene() const {
    return arms.size() > 1 || !arms.front().arm.empty() || !probes.empty() || !arms.front().tracked_objects.bodies.empty();
  }
};

// the arms on one simulated scene, the probes and the tracked objects watching it; the scene
// moves on once every arm wrote its torques
std::unique_ptr<runtime::NodeLogic> build_on_scene(const FollowerSetup& setup, const robot::SceneProbes& probes,
                                                   runtime::NodeContext& context) {
  const auto& spec = dynamic_cast<const robot::MujocoHardwareSpec&>(*setup.arms.front().hardware);
  robot::MujocoSceneConfig scene_config = spec.config();
  scene_config.period_s = 1.0 / context.node.rate_hz;
  auto scene = std::make_shared<robot::MujocoScene>(scene_config);
  std::vector<runtime::ArmGroup::Arm> group;
  for (const FollowerConfig& arm : setup.arms) {
    robot::MujocoHardwareConfig hardware = spec.config();
    hardware.joint_prefix = arm.joint_prefix;
    hardware.ee_site = arm.ee_site;
    group.push_back({arm.arm, std::make_unique<FollowerNode>(arm, std::make_unique<robot::MujocoHardware>(scene, hardware), context)});
  }
  for (const std::string& probe : setup.probes) group.push_back({"", probes.make(probe, scene)});
  if (!setup.arms.front().tracked_objects.bodies.empty()) {
    group.push_back({"", std::make_unique<ObjectPoseFeed>(setup.arms.front().tracked_objects, scene, context)});
  }
  return std::make_unique<runtime::ArmGroup>(std::move(group), [scene] { scene->step(); });
}

// the probes asked for exist and have a simulated world to watch
void check_probes(const ConfigNode& node, const FollowerSetup& setup, const robot::SceneProbes& probes) {
  for (const std::string& probe : setup.probes) {
    if (!probes.has(probe)) throw node.error("probes", "no probe '" + probe + "' in teleop_follower (it has: " + probes.names() + ")");
  }
  if (setup.shared_scene() && std::dynamic_pointer_cast<const robot::MujocoHardwareSpec>(setup.arms.front().hardware) == nullptr) {
    throw node.error("probes", "probes, tracked objects and arms watch a simulated scene: they need hardware: mujoco");
  }
}

const robot::SceneProbes& no_probes() {
  static const robot::SceneProbes none;
  return none;
}

}  // namespace

runtime::LogicParser follower_logic_parser(const robot::HardwareRegistry& hardware, const robot::SceneProbes& probes) {
  return [&hardware, &probes](const ConfigNode& root) -> runtime::LogicBuilder {
    const ConfigNode node = root.child("node");
    FollowerSetup setup{parse_follower_arms(root, hardware), node.get_string_list("probes")};
    check_probes(node, setup, probes);
    return [setup, &probes](runtime::NodeContext& context) -> std::unique_ptr<runtime::NodeLogic> {
      if (!setup.shared_scene()) return std::make_unique<FollowerNode>(setup.arms.front(), context);
      return build_on_scene(setup, probes, context);
    };
  };
}

runtime::LogicParser follower_logic_parser() { return follower_logic_parser(robot::simulated_hardware(), no_probes()); }

}  // namespace teleop::follower
