#include "teleop/follower/command_validator.h"

#include <algorithm>
#include <cmath>

namespace teleop::follower {

const char* to_string(CommandIssue issue) {
  switch (issue) {
    case CommandIssue::kWrongSize: return "rejected_wrong_size";
    case CommandIssue::kNonFinite: return "rejected_non_finite";
    case CommandIssue::kSequenceOld: return "rejected_old_sequence";
    case CommandIssue::kPositionLimit: return "clamped_position";
    case CommandIssue::kVelocityLimit: return "clamped_velocity";
    case CommandIssue::kGainLimit: return "clamped_gain";
    case CommandIssue::kTorqueLimit: return "clamped_torque";
    case CommandIssue::kCount: break;
  }
  return "?";
}

CommandValidator::CommandValidator(size_t joints, const JointLimits& limits) : joints_(joints), limits_(limits) {}

bool CommandValidator::sizes_ok(const msg::JointCommand& cmd) const {
  return cmd.mode().size() == joints_ && cmd.q_des_rad().size() == joints_ && cmd.dq_des_radps().size() == joints_ &&
         cmd.tau_ff_nm().size() == joints_ && cmd.stiffness_nm_per_rad().size() == joints_ &&
         cmd.damping_nms_per_rad().size() == joints_;
}

bool CommandValidator::all_finite(const msg::JointCommand& cmd) {
  const auto finite = [](const std::vector<double>& v) {
    return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
  };
  return finite(cmd.q_des_rad()) && finite(cmd.dq_des_radps()) && finite(cmd.tau_ff_nm()) &&
         finite(cmd.stiffness_nm_per_rad()) && finite(cmd.damping_nms_per_rad());
}

double CommandValidator::clamp_counted(double v, double lo, double hi, CommandIssue issue, bool& clamped) {
  if (v >= lo && v <= hi) return v;
  ++counts_[static_cast<size_t>(issue)];
  clamped = true;
  return std::clamp(v, lo, hi);
}

CommandVerdict CommandValidator::validate(const msg::JointCommand& cmd, ValidCommand& out) {
  CommandIssue reject_reason = CommandIssue::kCount;
  if (!sizes_ok(cmd)) {
    reject_reason = CommandIssue::kWrongSize;
  } else if (!all_finite(cmd)) {
    reject_reason = CommandIssue::kNonFinite;
  } else if (cmd.header().seq() <= last_seq_) {
    reject_reason = CommandIssue::kSequenceOld;
  }
  if (reject_reason != CommandIssue::kCount) {
    ++counts_[static_cast<size_t>(reject_reason)];
    ++rejected_;
    return CommandVerdict::kRejected;
  }
  last_seq_ = cmd.header().seq();
  bool clamped = false;
  const auto& l = limits_;
  for (size_t i = 0; i < joints_; ++i) {
    out.q_des_rad[i] = clamp_counted(cmd.q_des_rad()[i], l.q_min_rad[i], l.q_max_rad[i], CommandIssue::kPositionLimit, clamped);
    out.dq_des_radps[i] = clamp_counted(cmd.dq_des_radps()[i], -l.max_velocity_radps, l.max_velocity_radps,
                                        CommandIssue::kVelocityLimit, clamped);
    out.tau_ff_nm[i] = clamp_counted(cmd.tau_ff_nm()[i], -l.max_torque_nm, l.max_torque_nm, CommandIssue::kTorqueLimit, clamped);
    out.stiffness[i] = clamp_counted(cmd.stiffness_nm_per_rad()[i], 0.0, l.max_stiffness_nm_per_rad, CommandIssue::kGainLimit, clamped);
    out.damping[i] = clamp_counted(cmd.damping_nms_per_rad()[i], 0.0, l.max_damping_nms_per_rad, CommandIssue::kGainLimit, clamped);
  }
  return clamped ? CommandVerdict::kClamped : CommandVerdict::kAccepted;
}

}  // namespace teleop::follower
