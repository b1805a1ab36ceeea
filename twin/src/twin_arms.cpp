#include "twin_arms.h"

#include <memory>
#include <stdexcept>

#include "teleop/runtime/arm_configs.h"
#include "teleop/runtime/arm_group.h"
#include "teleop/sim/actuated_joints.h"
#include "twin_arm.h"
#include "twin_node.h"
#include "twin_scene.h"

namespace teleop::twin {
namespace {

std::unique_ptr<runtime::NodeLogic> build_arms(const std::vector<TwinConfig>& arms, runtime::NodeContext& context) {
  if (arms.size() == 1 && arms.front().arm.empty()) return std::make_unique<TwinNode>(arms.front(), context);
  TwinModelConfig model = arms.front().model;
  for (const TwinConfig& arm : arms) model.joint_prefixes.push_back(arm.joint_prefix);
  auto scene = std::make_unique<TwinScene>(model, arms.front().object_correction, context);
  std::vector<runtime::ArmGroup::Arm> group;
  std::vector<TwinArm*> twin_arms;
  size_t first = 0;
  for (const TwinConfig& arm : arms) {
    const size_t found = sim::find_actuated_joints(scene->simulation().simulation().model(), model.model_path,
                                                   arm.joint_prefix).count;
    if (found != arm.joints) {
      throw ConfigError("twin.joints is " + std::to_string(arm.joints) + " but " + model.model_path + " drives " +
                        std::to_string(found) + " joints named " + arm.joint_prefix + "* (twin.arms." + arm.arm + ")");
    }
    auto logic = std::make_unique<TwinArm>(arm, *scene, first, context);
    twin_arms.push_back(logic.get());
    group.push_back({arm.arm, std::move(logic)});
    first += arm.joints;
  }
  TwinScene* world = scene.get();
  group.push_back({"", std::move(scene)});
  // every arm wrote its target in its cycle: the world they share moves on, then each arm tells
  return std::make_unique<runtime::ArmGroup>(std::move(group), [world, twin_arms] {
    world->step();
    for (TwinArm* arm : twin_arms) arm->publish_step();
  });
}

}  // namespace

runtime::LogicParser twin_logic_parser() { return runtime::arm_logic_parser(parse_twin_arms, build_arms); }

}  // namespace teleop::twin
