#include "teleop/follower/command_validator.h"

#include <algorithm>
#include <cmath>

namespace teleop::follower {

const char* to_string(CommandIssue issue) {
  switch (issue) {
    case CommandIssue::kWrongSize: return "rejected_wrong_size";
    case CommandIssue::kNonFinite: return "rejected_non_finite";
    case CommandIssue::kSequenceOld: return "rejected_old_sequence";
    case CommandIssue::kUnknownMode: return "rejected_unknown_mode";
    case CommandIssue::kStale: return "rejected_stale";
    case CommandIssue::kMixedModes: return "rejected_mixed_modes";
    case CommandIssue::kBadOrientation: return "rejected_bad_orientation";
    case CommandIssue::kPositionLimit: return "clamped_position";
    case CommandIssue::kVelocityLimit: return "clamped_velocity";
    case CommandIssue::kGainLimit: return "clamped_gain";
    case CommandIssue::kTorqueLimit: return "clamped_torque";
    case CommandIssue::kWorkspaceLimit: return "clamped_workspace";
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

bool CommandValidator::all_finite(const msg::CartesianCommand& cmd) {
  const auto finite = [](const msg::Vector3& v) { return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z()); };
  const auto& o = cmd.target_pose().orientation();
  return finite(cmd.target_pose().position_m()) && std::isfinite(o.w()) && std::isfinite(o.x()) && std::isfinite(o.y()) &&
         std::isfinite(o.z()) && finite(cmd.target_twist().linear_mps()) && finite(cmd.target_twist().angular_radps()) &&
         finite(cmd.stiffness_translational_n_per_m()) && finite(cmd.stiffness_rotational_nm_per_rad()) &&
         std::isfinite(cmd.damping_ratio()) && std::isfinite(cmd.nullspace_stiffness_nm_per_rad());
}

bool CommandValidator::stale(const msg::SampleHeader& header, int64_t now_system_ns) const {
  const double age_s = static_cast<double>(now_system_ns - header.stamp_ns()) * 1e-9;
  return std::abs(age_s) > limits_.max_command_age_s;
}

CommandVerdict CommandValidator::reject(CommandIssue reason) {
  ++counts_[static_cast<size_t>(reason)];
  ++rejected_;
  last_rejection_ = reason;
  return CommandVerdict::kRejected;
}

double CommandValidator::clamp_counted(double v, double lo, double hi, CommandIssue issue, bool& clamped) {
  if (v >= lo && v <= hi) return v;
  ++counts_[static_cast<size_t>(issue)];
  clamped = true;
  return std::clamp(v, lo, hi);
}

CommandVerdict CommandValidator::validate(const msg::JointCommand& cmd, int64_t now_system_ns, ValidCommand& out,
                                          uint64_t session) {
  if (!sizes_ok(cmd)) return reject(CommandIssue::kWrongSize);
  if (!all_finite(cmd)) return reject(CommandIssue::kNonFinite);
  if (last_joint_.not_newer(session, cmd.header().seq())) return reject(CommandIssue::kSequenceOld);
  if (stale(cmd.header(), now_system_ns)) return reject(CommandIssue::kStale);
  const auto& modes = cmd.mode();
  // the wire carries the enum as a 32-bit number: anything may arrive
  const auto known = [](msg::ControlMode m) { return m >= msg::CONTROL_GRAVITY && m <= msg::CONTROL_POSITION_PD; };
  if (!std::all_of(modes.begin(), modes.end(), known)) return reject(CommandIssue::kUnknownMode);
  if (modes.empty() || modes[0] == msg::CONTROL_CARTESIAN_IMPEDANCE ||
      std::any_of(modes.begin(), modes.end(), [&](msg::ControlMode m) { return m != modes[0]; })) {
    // one controller runs the whole arm; Cartesian targets come as CartesianCommand
    return reject(CommandIssue::kMixedModes);
  }
  last_joint_ = {session, cmd.header().seq()};
  out.mode = modes[0];
  bool clamped = false;
  const auto& l = limits_;
  for (size_t i = 0; i < joints_; ++i) {
    out.q_des_rad[i] = clamp_counted(cmd.q_des_rad()[i], l.q_min_rad[i], l.q_max_rad[i], CommandIssue::kPositionLimit, clamped);
    out.dq_des_radps[i] = clamp_counted(cmd.dq_des_radps()[i], -l.max_velocity_radps, l.max_velocity_radps,
                                        CommandIssue::kVelocityLimit, clamped);
    out.tau_ff_nm[i] =
        clamp_counted(cmd.tau_ff_nm()[i], -l.max_torque_nm[i], l.max_torque_nm[i], CommandIssue::kTorqueLimit, clamped);
    out.stiffness[i] = clamp_counted(cmd.stiffness_nm_per_rad()[i], 0.0, l.max_stiffness_nm_per_rad, CommandIssue::kGainLimit, clamped);
    out.damping[i] = clamp_counted(cmd.damping_nms_per_rad()[i], 0.0, l.max_damping_nms_per_rad, CommandIssue::kGainLimit, clamped);
  }
  return clamped ? CommandVerdict::kClamped : CommandVerdict::kAccepted;
}

CommandVerdict CommandValidator::validate(const msg::CartesianCommand& cmd, int64_t now_system_ns, ValidCommand& out,
                                          uint64_t session) {
  if (!all_finite(cmd)) return reject(CommandIssue::kNonFinite);
  if (last_cartesian_.not_newer(session, cmd.header().seq())) return reject(CommandIssue::kSequenceOld);
  if (stale(cmd.header(), now_system_ns)) return reject(CommandIssue::kStale);
  const auto& o = cmd.target_pose().orientation();
  const double norm = std::sqrt(o.w() * o.w() + o.x() * o.x() + o.y() * o.y() + o.z() * o.z());
  // a little off unit is rounding and gets normalised; far off is a bug at the sender
  if (std::abs(norm - 1.0) > 0.01) return reject(CommandIssue::kBadOrientation);
  last_cartesian_ = {session, cmd.header().seq()};
  out.mode = msg::CONTROL_CARTESIAN_IMPEDANCE;
  out.orientation_wxyz = {o.w() / norm, o.x() / norm, o.y() / norm, o.z() / norm};

  bool clamped = false;
  const auto& l = limits_;
  const auto& p = cmd.target_pose().position_m();
  const std::array<double, 3> position{p.x(), p.y(), p.z()};
  const auto& v = cmd.target_twist().linear_mps();
  const auto& w = cmd.target_twist().angular_radps();
  const std::array<double, 6> twist{v.x(), v.y(), v.z(), w.x(), w.y(), w.z()};
  const auto& kt = cmd.stiffness_translational_n_per_m();
  const auto& kr = cmd.stiffness_rotational_nm_per_rad();
  const std::array<double, 3> k_trans{kt.x(), kt.y(), kt.z()};
  const std::array<double, 3> k_rot{kr.x(), kr.y(), kr.z()};
  for (size_t i = 0; i < 3; ++i) {
    out.x_des_m[i] = clamp_counted(position[i], l.workspace_min_m[i], l.workspace_max_m[i], CommandIssue::kWorkspaceLimit, clamped);
    out.twist_des[i] = clamp_counted(twist[i], -l.max_linear_velocity_mps, l.max_linear_velocity_mps, CommandIssue::kVelocityLimit, clamped);
    out.twist_des[i + 3] =
        clamp_counted(twist[i + 3], -l.max_angular_velocity_radps, l.max_angular_velocity_radps, CommandIssue::kVelocityLimit, clamped);
    out.translational_stiffness_n_per_m[i] =
        clamp_counted(k_trans[i], 0.0, l.max_translational_stiffness_n_per_m, CommandIssue::kGainLimit, clamped);
    out.rotational_stiffness_nm_per_rad[i] =
        clamp_counted(k_rot[i], 0.0, l.max_rotational_stiffness_nm_per_rad, CommandIssue::kGainLimit, clamped);
  }
  out.damping_ratio = clamp_counted(cmd.damping_ratio(), 0.1, 2.0, CommandIssue::kGainLimit, clamped);
  out.nullspace_stiffness_nm_per_rad =
      clamp_counted(cmd.nullspace_stiffness_nm_per_rad(), 0.0, l.max_nullspace_stiffness_nm_per_rad, CommandIssue::kGainLimit, clamped);
  return clamped ? CommandVerdict::kClamped : CommandVerdict::kAccepted;
}

}  // namespace teleop::follower
