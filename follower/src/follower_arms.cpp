#include "teleop/follower/follower_arms.h"

#include <memory>

#include "teleop/follower/box_task_trace.h"
#include "teleop/follower/follower_node.h"
#include "teleop/follower/mujoco_hardware.h"
#include "teleop/follower/object_pose_feed.h"
#include "teleop/runtime/arm_configs.h"
#include "teleop/runtime/arm_group.h"

namespace teleop::follower {
namespace {

std::unique_ptr<runtime::NodeLogic> build_arms(const std::vector<FollowerConfig>& arms, runtime::NodeContext& context) {
  if (arms.size() == 1 && arms.front().arm.empty()) return std::make_unique<FollowerNode>(arms.front(), context);
  MujocoSceneConfig scene_config = arms.front().mujoco;
  scene_config.period_s = 1.0 / context.node.rate_hz;
  auto scene = std::make_shared<MujocoScene>(scene_config);
  std::vector<runtime::ArmGroup::Arm> group;
  for (const FollowerConfig& arm : arms) {
    group.push_back({arm.arm, std::make_unique<FollowerNode>(arm, std::make_unique<MujocoHardware>(scene, arm.mujoco), context)});
  }
  if (arms.front().trace_box_task) group.push_back({"", std::make_unique<BoxTaskTrace>(scene)});
  if (!arms.front().tracked_objects.bodies.empty()) {
    group.push_back({"", std::make_unique<ObjectPoseFeed>(arms.front().tracked_objects, scene, context)});
  }
  // each arm wrote its torques in its cycle: now the world they share moves on
  return std::make_unique<runtime::ArmGroup>(std::move(group), [scene] { scene->step(); });
}

}  // namespace

runtime::LogicParser follower_logic_parser() { return runtime::arm_logic_parser(parse_follower_arms, build_arms); }

}  // namespace teleop::follower
