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

#include "teleop/common/config.h"

namespace teleop::runtime {

enum class Architecture { kPositionPosition, kPfc, kPfcTdpa, kMmt };

const char* to_string(Architecture architecture);

/// True when the leader commands the follower in Cartesian space (pfc, pfc_tdpa).
constexpr bool is_cartesian(Architecture a) { return a == Architecture::kPfc || a == Architecture::kPfcTdpa; }

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
  Architecture architecture = Architecture::kPositionPosition;
  TdpaSettings tdpa;
};

/// Reads the optional `teleoperation:` section of a node config; nullopt when absent.
/// Throws ConfigError naming file and key.
std::optional<TeleoperationConfig> parse_teleoperation_config(const ConfigNode& root);

}  // namespace teleop::runtime
