#include "teleop/leader/leader_arms.h"

#include <memory>

#include "teleop/common/joint_config.h"
#include "teleop/runtime/arm_configs.h"
#include "teleop/runtime/arm_group.h"
#include "teleop/sim/model_config.h"

namespace teleop::leader {
namespace {

// a hand's own keys on top of the shared `leader:` section
LeaderConfig arm_config(const LeaderConfig& shared, const std::string& name, const ConfigNode& a) {
  LeaderConfig c = shared;
  c.arm = name;
  // the hand's device is mounted like the robot's arm: one model for the device and the mapping
  c.arm_model = sim::get_model_path(a, "model");
  c.haptic_arm.model.model_path = c.arm_model;
  c.ee_site = a.get_string("ee_site");
  c.home_rad = read_joint_list(a, "home_rad", c.joints, kJointAngleRange, 0.0);
  c.motion.home_rad = c.home_rad;
  if (c.motion.kind == OperatorMotionConfig::Kind::kRecorded) {
    c.motion.recording = load_recording(a, "recording", c.motion);
  } else if (a.has("recording")) {
    throw a.error("recording", "only for leader.motion: recorded");
  }
  return c;
}

std::unique_ptr<runtime::NodeLogic> build_arms(const std::vector<LeaderConfig>& arms, runtime::NodeContext& context) {
  if (arms.size() == 1 && arms.front().arm.empty()) return std::make_unique<LeaderNode>(arms.front(), context);
  std::vector<runtime::ArmGroup::Arm> group;
  for (const LeaderConfig& arm : arms) group.push_back({arm.arm, std::make_unique<LeaderNode>(arm, context)});
  return std::make_unique<runtime::ArmGroup>(std::move(group));
}

}  // namespace

std::vector<LeaderConfig> parse_leader_arms(const ConfigNode& root) {
  return runtime::read_arm_configs(root.child("leader"), LeaderNode::parse_config(root), arm_config);
}

runtime::LogicParser leader_logic_parser() { return runtime::arm_logic_parser(parse_leader_arms, build_arms); }

}  // namespace teleop::leader
