#pragma once
// Checks every command before it reaches the controllers: malformed, non-finite, stale or
// out-of-order commands are rejected, out-of-limit values clamped, and each case counted by
// reason (reported in the node report and, as FAULT_COMMAND_REJECTED, in NodeStatus).

#include <array>
#include <cstdint>

#include <teleop/msg/arm.h>

#include "teleop/common/joint_model.h"

namespace teleop::follower {

struct JointLimits {
  JointVector q_min_rad{};
  JointVector q_max_rad{};
  double max_velocity_radps = 2.0;
  double max_stiffness_nm_per_rad = 5000.0;
  double max_damping_nms_per_rad = 500.0;
  /// Per joint; the torque saturation of the output uses the same values.
  JointVector max_torque_nm = filled(80.0);
  /// Commands stamped longer ago than this (CLOCK_REALTIME of the sender) are rejected; the
  /// same bound applies to stamps in the future (clock skew). Infinite: no check (`off` in YAML).
  double max_command_age_s = 0.5;
  // Cartesian commands, in the arm's base frame
  std::array<double, 3> workspace_min_m{-1.0, -1.0, -0.2};
  std::array<double, 3> workspace_max_m{1.0, 1.0, 1.4};
  double max_translational_stiffness_n_per_m = 3000.0;
  double max_rotational_stiffness_nm_per_rad = 300.0;
  double max_nullspace_stiffness_nm_per_rad = 100.0;
  double max_linear_velocity_mps = 1.0;
  double max_angular_velocity_radps = 2.5;

  static JointVector filled(double v) {
    JointVector a{};
    a.fill(v);
    return a;
  }
};

enum class CommandVerdict { kAccepted, kClamped, kRejected };

/// Why a command was rejected or clamped.
enum class CommandIssue : size_t {
  kWrongSize,       ///< a joint sequence does not have one value per joint
  kNonFinite,       ///< NaN or Inf anywhere
  kSequenceOld,     ///< sequence number not newer than the last accepted one of its session
  kUnknownMode,     ///< a control mode outside msg::ControlMode
  kStale,           ///< stamped longer ago (or further ahead) than max_command_age_s
  kMixedModes,      ///< joints asking for different control modes (one mode per arm)
  kBadOrientation,  ///< a Cartesian orientation that is not a rotation (|q| far from 1)
  kPositionLimit,   ///< q_des outside [q_min, q_max]: clamped
  kVelocityLimit,   ///< |dq_des| or the Cartesian twist above the limit: clamped
  kGainLimit,       ///< stiffness/damping negative or above the limit: clamped
  kTorqueLimit,     ///< |tau_ff| above the limit: clamped
  kWorkspaceLimit,  ///< Cartesian target outside the workspace box: clamped
  kCount
};

const char* to_string(CommandIssue issue);

/// The part of a command the controllers use, after validation.
struct ValidCommand {
  msg::ControlMode mode = msg::CONTROL_JOINT_IMPEDANCE;
  JointVector q_des_rad{};
  JointVector dq_des_radps{};
  JointVector tau_ff_nm{};
  JointVector stiffness{};
  JointVector damping{};
  // Cartesian impedance (mode CONTROL_CARTESIAN_IMPEDANCE), the arm's base frame
  std::array<double, 3> x_des_m{};
  std::array<double, 4> orientation_wxyz{1, 0, 0, 0};  ///< unit
  std::array<double, 6> twist_des{};                   ///< linear [m/s], angular [rad/s]
  std::array<double, 3> translational_stiffness_n_per_m{};
  std::array<double, 3> rotational_stiffness_nm_per_rad{};
  double damping_ratio = 1.0;
  double nullspace_stiffness_nm_per_rad = 0.0;
};

class CommandValidator {
 public:
  CommandValidator(size_t joints, const JointLimits& limits);

  /// Validates `cmd` into `out` (all fields of a joint command). Real-time safe. `out` is only
  /// written when not rejected. `now_system_ns`: CLOCK_REALTIME now, for the age check.
  /// `session`: the writer session the command came in (transport::Subscription::session());
  /// sequence numbers are compared within one session only, so a restarted sender's commands
  /// (numbered from 1 again) are taken from its first.
  [[nodiscard]] CommandVerdict validate(const msg::JointCommand& cmd, int64_t now_system_ns, ValidCommand& out,
                                        uint64_t session = 1);
  /// The same for a Cartesian command: writes the Cartesian fields and sets the mode.
  [[nodiscard]] CommandVerdict validate(const msg::CartesianCommand& cmd, int64_t now_system_ns, ValidCommand& out,
                                        uint64_t session = 1);

  uint64_t count(CommandIssue issue) const { return counts_[static_cast<size_t>(issue)]; }
  uint64_t rejected() const { return rejected_; }
  /// Why the last rejected command was rejected (kCount before any).
  CommandIssue last_rejection() const { return last_rejection_; }
  const JointLimits& limits() const { return limits_; }

 private:
  bool sizes_ok(const msg::JointCommand& cmd) const;
  static bool all_finite(const msg::JointCommand& cmd);
  static bool all_finite(const msg::CartesianCommand& cmd);
  bool stale(const msg::SampleHeader& header, int64_t now_system_ns) const;
  /// Counts and returns kRejected when `reason` is set (not kCount).
  CommandVerdict reject(CommandIssue reason);
  double clamp_counted(double v, double lo, double hi, CommandIssue issue, bool& clamped);

  /// The newest command accepted from one stream: its session and sequence number.
  struct StreamPosition {
    uint64_t session = 0;
    uint64_t seq = 0;
    /// True when `seq_of` of `session_of` is not newer than this position (a writer numbers from
    /// 1: a 0 is never newer).
    bool not_newer(uint64_t session_of, uint64_t seq_of) const {
      return seq_of == 0 || (session_of == session && seq_of <= seq);
    }
  };

  size_t joints_;
  JointLimits limits_;
  StreamPosition last_joint_;
  StreamPosition last_cartesian_;
  uint64_t rejected_ = 0;
  CommandIssue last_rejection_ = CommandIssue::kCount;
  std::array<uint64_t, static_cast<size_t>(CommandIssue::kCount)> counts_{};
};

}  // namespace teleop::follower
