#pragma once
// Checks every joint command before it reaches the controller: malformed or non-finite
// commands are rejected, out-of-limit targets clamped, and each case counted by reason.

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
  double max_torque_nm = 80.0;
};

enum class CommandVerdict { kAccepted, kClamped, kRejected };

/// Why a command was rejected or clamped.
enum class CommandIssue : size_t {
  kWrongSize,      ///< a joint sequence does not have one value per joint
  kNonFinite,      ///< NaN or Inf anywhere
  kSequenceOld,    ///< sequence number not newer than the last accepted one
  kPositionLimit,  ///< q_des outside [q_min, q_max]: clamped
  kVelocityLimit,  ///< |dq_des| above the limit: clamped
  kGainLimit,      ///< stiffness/damping negative or above the limit: clamped
  kTorqueLimit,    ///< |tau_ff| above the limit: clamped
  kCount
};

const char* to_string(CommandIssue issue);

/// The part of a command the controller uses, after validation.
struct ValidCommand {
  JointVector q_des_rad{};
  JointVector dq_des_radps{};
  JointVector tau_ff_nm{};
  JointVector stiffness{};
  JointVector damping{};
};

class CommandValidator {
 public:
  CommandValidator(size_t joints, const JointLimits& limits);

  /// Validates `cmd` into `out`. Real-time safe. `out` is only written when not rejected.
  [[nodiscard]] CommandVerdict validate(const msg::JointCommand& cmd, ValidCommand& out);

  uint64_t count(CommandIssue issue) const { return counts_[static_cast<size_t>(issue)]; }
  uint64_t rejected() const { return rejected_; }

 private:
  bool sizes_ok(const msg::JointCommand& cmd) const;
  static bool all_finite(const msg::JointCommand& cmd);
  double clamp_counted(double v, double lo, double hi, CommandIssue issue, bool& clamped);

  size_t joints_;
  JointLimits limits_;
  uint64_t last_seq_ = 0;
  uint64_t rejected_ = 0;
  std::array<uint64_t, static_cast<size_t>(CommandIssue::kCount)> counts_{};
};

}  // namespace teleop::follower
