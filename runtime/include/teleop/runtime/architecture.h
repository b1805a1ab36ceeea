#pragma once
// The teleoperation architecture a scenario runs (docs/architectures.md). Every node of the
// scenario reads the same `teleoperation:` section and plays its part:
//   position_position  leader sends joint positions; feels K (q_f - q_l) from the follower's state
//   pfc                leader sends its end-effector pose and twist (Cartesian impedance on the
//                      follower); feels the follower's estimated external wrench
//   pfc_tdpa           pfc with the Time Domain Passivity Approach on both ends of the channel
//   mmt                model-mediated: leader coupled to the local twin and feels it; the twin
//                      commands the follower; the follower's measurements correct the twin

#include <limits>
#include <optional>
#include <span>
#include <string_view>

#include "teleop/common/config.h"

namespace teleop::runtime {

/// Whose commands the follower tracks under an architecture, and in which space.
enum class CommandPath {
  kLeaderJoint,      ///< the leader's joint impedance commands (teleop/leader/joint_command)
  kLeaderCartesian,  ///< the leader's Cartesian commands, with a TDPA channel beside them
  kTwin,             ///< the twin's joint commands (teleop/twin/joint_command): model-mediated
};

/// One architecture of the registry: its name in `teleoperation.architecture` and what every node
/// of a scenario reads from it to play its part. The leader's part is a strategy of its own
/// (leader/src/architectures/, one file per architecture, registered by this name); the follower
/// and the twin play theirs from `commands` and `tdpa_corrects`.
struct Architecture {
  std::string_view name;
  CommandPath commands = CommandPath::kLeaderJoint;
  /// The TDPA controllers correct the channel (pfc_tdpa); false: a Cartesian channel's energy
  /// balance is only observed (pfc reports it).
  bool tdpa_corrects = false;
};

/// The registry: the architectures every build knows, the default (position_position) first. A
/// static table (architecture.cpp), no registration at start-up: docs/architecture.md, "A new
/// teleoperation architecture".
std::span<const Architecture> architectures();
/// The architecture of that name; nullptr when there is none.
const Architecture* find_architecture(std::string_view name);

/// True when the leader commands the follower in Cartesian space (pfc, pfc_tdpa).
inline bool is_cartesian(const Architecture& a) { return a.commands == CommandPath::kLeaderCartesian; }

struct TdpaSettings {
  /// Limits of the adaptive dampers: alpha [N s/m] at the leader, beta [m/(N s)] at the
  /// follower (the same number for the rotational channels in N m s/rad, rad/(N m s)); infinity:
  /// none (the corrected quantity never changes sign, so unlimited is stable, only less smooth).
  double max_leader_damping = std::numeric_limits<double>::infinity();
  double max_follower_damping = std::numeric_limits<double>::infinity();
  /// The follower's drift compensation (control/drift_compensation.h): the time constant with
  /// which the reference's drift is asked back [s], 0: none; and the largest speeds it may use.
  double drift_time_constant_s = 0.0;
  double drift_max_speed_m_per_s = 0.05;
  double drift_max_speed_rad_per_s = 0.2;
  /// A Cartesian channel whose estimated external force [N] / torque [N m] exceeds this is in
  /// contact: its drift waits (free motion only).
  double drift_contact_force_n = 3.0;
  double drift_contact_torque_nm = 0.5;
};

struct TeleoperationConfig {
  /// An entry of architectures(), never null.
  const Architecture* architecture = &architectures().front();
  TdpaSettings tdpa;
};

/// Reads the optional `teleoperation:` section of a node config; nullopt when absent.
/// Throws ConfigError naming file and key (an unknown architecture: the registry's names and
/// the nearest to the one given).
std::optional<TeleoperationConfig> parse_teleoperation_config(const ConfigNode& root);

}  // namespace teleop::runtime
