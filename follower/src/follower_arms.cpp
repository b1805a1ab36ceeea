#include "teleop/follower/follower_arms.h"

#include <memory>

#include "teleop/common/joint_config.h"
#include "teleop/follower/box_task_trace.h"
#include "teleop/follower/follower_node.h"
#include "teleop/follower/mujoco_hardware.h"
#include "teleop/follower/object_pose_feed.h"
#include "teleop/runtime/arm_configs.h"
#include "teleop/runtime/arm_group.h"
#include "teleop/sim/model_config.h"

namespace teleop::follower {
namespace {

// an arm's own keys on top of the shared `follower:` section
FollowerConfig arm_config(const FollowerConfig& shared, const std::string& name, const ConfigNode& a) {
  FollowerConfig c = shared;
  c.arm = name;
  c.mujoco.joint_prefix = a.get_string("joint_prefix");
  c.mujoco.ee_site = a.get_string("ee_site");
  c.control.model_path = sim::get_model_path(a, "control_model");
  c.control.ee_site = c.mujoco.ee_site;
  if (a.has("rest_posture_rad")) {
    const JointVector rest = read_joint_list(a, "rest_posture_rad", c.joints, kJointAngleRange, 0.0);
    c.control.rest_posture_rad = Eigen::Map<const control::JointVector>(rest.data());
  }
  return c;
}

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

std::vector<FollowerConfig> parse_follower_arms(const ConfigNode& root) {
  return runtime::read_arm_configs(root.child("follower"), parse_follower_config(root), arm_config);
}

runtime::LogicParser follower_logic_parser() { return runtime::arm_logic_parser(parse_follower_arms, build_arms); }

}  // namespace teleop::follower
