#include "teleop/leader/leader_arms.h"

#include <memory>

#include "leader_config.h"
#include "leader_node.h"
#include "teleop/runtime/arm_configs.h"
#include "teleop/runtime/arm_group.h"

namespace teleop::leader {
namespace {

std::unique_ptr<runtime::NodeLogic> build_arms(const std::vector<LeaderConfig>& arms, runtime::NodeContext& context) {
  if (arms.size() == 1 && arms.front().arm.empty()) return std::make_unique<LeaderNode>(arms.front(), context);
  std::vector<runtime::ArmGroup::Arm> group;
  for (const LeaderConfig& arm : arms) group.push_back({arm.arm, std::make_unique<LeaderNode>(arm, context)});
  return std::make_unique<runtime::ArmGroup>(std::move(group));
}

}  // namespace

runtime::LogicParser leader_logic_parser(const DeviceRegistry& devices) {
  return runtime::arm_logic_parser([&devices](const ConfigNode& root) { return parse_leader_arms(root, devices); },
                                   build_arms);
}

}  // namespace teleop::leader
