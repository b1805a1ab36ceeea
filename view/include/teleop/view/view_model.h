#pragma once
// What `teleop view` and `teleop render` show: the scene of a node's configuration (the
// follower's simulated world, or the twin's model), and which joints of it each arm's samples pose.

#include <string>
#include <vector>

namespace teleop::view {

/// One arm of the scene: its name ("" for a one-arm robot: the plain topic names), the prefix
/// of its joints in the model ("left_"; "" for every actuated hinge joint) and its flange site,
/// where its external wrench acts ("": <prefix>ee_site when the model has it).
struct ViewArm {
  std::string name;
  std::string joint_prefix;
  std::string ee_site;
  /// Joints posed by name, in the samples' order (the hand's 20 joints, of which only the 9 main
  /// ones have actuators); empty: the actuated joints with `joint_prefix`, in actuator order.
  std::vector<std::string> joint_names;
  /// The one topic whose JointState poses it, solid (the hand's teleop/hand/joint_state); empty:
  /// the follower's, twin's and leader's arm topics.
  std::string state_topic;
};

struct ViewModelSpec {
  /// The MJCF file (absolute, or relative to the working directory).
  std::string model_path;
  /// The keyframe the model starts in ("" for the model's default pose): what is not posed by a
  /// sample (a mobile base standing still, an object nobody tracks) stays there.
  std::string keyframe;
  std::vector<ViewArm> arms;
  /// The config it came from and the section read (`follower`, `twin`): for messages.
  std::string source;
};

/// Reads the scene of a follower, twin or hand node config (a file): the follower's simulated world
/// (`follower.mujoco.model`, or the controller's own `follower.control.model` of a real arm) or the
/// twin's `twin.model.file`, its keyframe, and the arms of `<section>.arms`; for a hand config
/// (`hand:` section, whose node knows no model) the emulator's MuJoCo hand
/// (config/models/svh_hand_grasp.xml), its 20 joints posed by name from teleop/hand/joint_state.
/// Only these keys are read; the node itself checks the rest. Throws ConfigError naming the file
/// and key when the config has none of these sections or a model that is missing.
ViewModelSpec read_view_model(const std::string& node_config_path);

/// The MuJoCo hand a hand config is shown on: the one `teleop_hand_emulator --plant mujoco` runs.
inline constexpr const char* kHandViewModel = "config/models/svh_hand_grasp.xml";

/// The shipped node config `name` (config/nodes/<name>.yaml, installed or in the source tree),
/// whatever the working directory holds. Throws ConfigError saying where it looked.
std::string shipped_node_config(const std::string& name);

}  // namespace teleop::view
