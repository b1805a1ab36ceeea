#include "teleop/view/view_model.h"

#include "teleop/common/config.h"
#include "teleop/common/data_paths.h"
#include "teleop/hand/hand_coupling.h"
#include "teleop/transport/topics.h"

namespace teleop::view {
namespace {

std::vector<ViewArm> read_arms(const ConfigNode& section) {
  std::vector<ViewArm> arms;
  if (const auto named = section.optional_child("arms")) {
    for (const std::string& name : named->keys()) {
      const ConfigNode arm = named->child(name);
      arms.push_back({name, arm.get_string("joint_prefix"), arm.get_string("ee_site", "")});
    }
  }
  if (arms.empty()) {
    // a one-arm follower names its flange in follower.control (default ee_site)
    const auto control = section.optional_child("control");
    arms.push_back({"", "", control ? control->get_string("ee_site", "") : ""});
  }
  return arms;
}

// the hand node publishes its 20 joints (the coupling's output) on one topic; its config names
// no model, the view shows the emulator's
ViewModelSpec hand_view_model(const ConfigNode& root, const std::string& node_config_path) {
  ViewModelSpec spec;
  spec.source = node_config_path + " (hand)";
  spec.model_path = find_data(kHandViewModel, kHandViewModel).string();
  if (spec.model_path.empty()) {
    throw root.error("hand", std::string("the hand's MuJoCo model was not found: looked in ") +
                                 data_candidates_text(kHandViewModel, kHandViewModel, DataRoots::current()));
  }
  ViewArm hand;
  hand.name = "hand";
  hand.state_topic = transport::topics::kHandJoints.name;
  for (const std::string_view joint : hand::kHandJointNames) hand.joint_names.emplace_back(joint);
  spec.arms.push_back(hand);
  return spec;
}

}  // namespace

ViewModelSpec read_view_model(const std::string& node_config_path) {
  const ConfigNode root = ConfigNode::load_file(node_config_path);
  ViewModelSpec spec;
  if (const auto follower = root.optional_child("follower")) {
    spec.source = node_config_path + " (follower)";
    const auto mujoco = follower->optional_child("mujoco");
    if (mujoco && follower->get_string("hardware", "mujoco") == "mujoco") {
      spec.model_path = mujoco->get_path("model");
      spec.keyframe = mujoco->get_string("keyframe", "");
    } else {
      // a real arm: the controller's model of it (one arm, no world around it)
      spec.model_path = follower->child("control").get_path("model");
    }
    spec.arms = read_arms(*follower);
    return spec;
  }
  if (const auto twin = root.optional_child("twin")) {
    spec.source = node_config_path + " (twin)";
    const ConfigNode model = twin->child("model");
    spec.model_path = model.get_path("file");
    spec.keyframe = model.get_string("keyframe", "");
    spec.arms = read_arms(*twin);
    return spec;
  }
  if (root.optional_child("hand")) return hand_view_model(root, node_config_path);
  throw root.error("follower",
                   "no follower, twin or hand section: `teleop view` shows the scene of a follower, twin or hand "
                   "config");
}

std::string shipped_node_config(const std::string& name) {
  const std::filesystem::path path = find_named_config("nodes", name);
  if (path.empty()) {
    const std::string file = "config/nodes/" + name + ".yaml";
    throw ConfigError(name + ": no shipped node config, looked in " +
                      data_candidates_text(file, file, DataRoots::current()));
  }
  return path.string();
}

}  // namespace teleop::view
