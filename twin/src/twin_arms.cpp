#include "teleop/twin/twin_arms.h"

#include <memory>
#include <stdexcept>

#include "teleop/runtime/arm_configs.h"
#include "teleop/runtime/arm_group.h"
#include "teleop/sim/actuated_joints.h"
#include "teleop/twin/twin_arm.h"
#include "teleop/twin/twin_node.h"
#include "teleop/twin/twin_scene.h"

namespace teleop::twin {
namespace {

// an arm's own keys on top of the shared `twin:` section
TwinConfig arm_config(const TwinConfig& shared, const std::string& name, const ConfigNode& a) {
  TwinConfig c = shared;
  c.arm = name;
  c.joint_prefix = a.get_string("joint_prefix");
  if (c.joint_prefix.empty()) throw a.error("joint_prefix", "must not be empty: it tells this arm's joints from the others'");
  return c;
}

// what only the one-arm twin does
void refuse_one_arm_features(const ConfigNode& section, const TwinConfig& shared) {
  if (shared.mode != TwinMode::kRealtime) {
    throw section.error("arms", "mode: lockstep and mode: hil run one arm only; a twin with arms runs mode: realtime");
  }
  if (shared.mmt.correction) {
    throw section.child("mmt").error("correction", "model correction runs on one arm only, not with twin.arms");
  }
}

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

std::vector<TwinConfig> parse_twin_arms(const ConfigNode& root) {
  const ConfigNode section = root.child("twin");
  const TwinConfig shared = parse_twin_config(root);
  if (section.has("arms")) refuse_one_arm_features(section, shared);
  if (!section.has("arms") && shared.object_correction) {
    throw section.error("object_correction", "corrects the shared objects of a twin with arms (twin.arms) only");
  }
  return runtime::read_arm_configs(section, shared, arm_config);
}

runtime::LogicParser twin_logic_parser() { return runtime::arm_logic_parser(parse_twin_arms, build_arms); }

}  // namespace teleop::twin
