#pragma once
// Configuration of the twin node (`twin:` section, config/nodes/twin*.yaml, docs/twin.md).

#include <optional>
#include <string>
#include <vector>

#include "teleop/common/config.h"
#include "teleop/common/joint_model.h"
#include "environment_correction.h"
#include "object_correction.h"
#include "teleop/twin/twin_model_config.h"

namespace teleop::twin {

enum class TwinMode {
  /// Paced by the wall clock, coupled to a robot's joint state (PARTI eq. 2), renders eq. 3.
  kRealtime,
  /// Strictly alternating with an external controller process (thesis §3.4).
  kLockstep,
  /// The follower's measured state supersedes the twin's; the twin's controller commands it.
  kHil,
};

struct LockstepConfig {
  /// A command not there this long after the state went out: the controller stalled.
  double timeout_s = 1.0;
  /// Steps to run, then the node ends its run (0: until stopped).
  uint64_t steps = 0;
  /// Where to write the trajectory (one line per step, hex floats: bit-exact); "" = nowhere.
  std::string trajectory_file;
};

struct HilConfig {
  /// The controller: a smooth joint trajectory from the measured start to `goal_rad` over
  /// `move_time_s`, sent as joint impedance commands.
  JointVector goal_rad{};
  size_t goal_joints = 0;
  double move_time_s = 2.0;
  double stiffness_nm_per_rad = 400.0;
  double damping_nms_per_rad = 30.0;
  /// Topic the command goes to: the twin's own (a follower with command_source: twin), or the
  /// leader's (a follower from before that option, the twin standing in for the leader).
  enum class CommandTopic { kTwin, kLeader } command_topic = CommandTopic::kTwin;
  /// The follower silent longer than this: stop commanding.
  double peer_timeout_s = 0.1;
};

/// Model-mediated teleoperation (teleoperation.architecture: mmt): the twin, coupled to the
/// leader, commands the follower with its own joint state (joint impedance).
struct MmtConfig {
  bool enabled = false;
  double stiffness_nm_per_rad = 400.0;
  double damping_nms_per_rad = 20.0;
  /// The follower's measurements correct the twin's environment (absent: the model is trusted).
  std::optional<CorrectionConfig> correction;
};

struct TwinConfig {
  /// The arm of a multi-arm twin this config is for (twin.arms; its topics are T/<arm>), "" for
  /// the one arm of a one-arm twin (plain topics).
  std::string arm;
  /// The arm's joints in the model: those whose names start with this ("" for a one-arm twin).
  std::string joint_prefix;
  TwinMode mode = TwinMode::kRealtime;
  /// Joints of the coupled robot; the model must drive exactly these.
  size_t joints = 7;
  TwinModelConfig model;
  /// Whose joint state the twin is coupled to in real-time mode.
  enum class CoupledTo { kLeader, kFollower } coupled_to = CoupledTo::kLeader;
  /// lambda of PARTI eq. 3 and the cutoff of its low-pass filter (0: unfiltered).
  double feedback_gain = 0.5;
  double feedback_cutoff_hz = 30.0;
  /// Coupled robot silent longer than this: stop rendering feedback.
  double peer_timeout_s = 0.1;
  /// Joint speed at which the twin joins its coupled robot again after a hold (coupled_robot.h).
  double rejoin_speed_radps = 0.5;
  LockstepConfig lockstep;
  HilConfig hil;
  MmtConfig mmt;
  /// The remote site's measured objects pull the twin's (twin.arms only; absent: none).
  std::optional<ObjectCorrectionConfig> object_correction;
};

/// Reads the `twin:` section of `root`. Throws ConfigError naming file and key.
TwinConfig parse_twin_config(const ConfigNode& root);

/// One config per arm of `twin.arms` (each on its joint prefix of the shared scene), in the
/// file's order; a single unnamed arm without it. Throws ConfigError naming file and key.
std::vector<TwinConfig> parse_twin_arms(const ConfigNode& root);

}  // namespace teleop::twin
