#include "position_position.h"

#include "teleop/transport/arm_topic.h"
#include "teleop/transport/joint_fields.h"

namespace teleop::leader {

PositionPositionLeader::PositionPositionLeader(const LeaderSetup& setup)
    : config_(setup.config),
      follower_state_(setup.peers.follower_state),
      command_(setup.context.participant, transport::arm_topic(transport::topics::kLeaderCommand, setup.config.arm),
               setup.context.node.name) {
  setup.peers.twin_feedback.mark_optional();  // only MMT renders the twin's forces
  auto& cmd = command_.sample();
  cmd.robot("follower");
  cmd.arm(transport::arm_label(config_.arm));
  cmd.mode().assign(config_.joints, msg::CONTROL_JOINT_IMPEDANCE);
  transport::presize(config_.joints, cmd.q_des_rad(), cmd.dq_des_radps(), cmd.tau_ff_nm());
  cmd.stiffness_nm_per_rad().assign(config_.joints, config_.stiffness_nm_per_rad);
  cmd.damping_nms_per_rad().assign(config_.joints, config_.damping_nms_per_rad);
}

void PositionPositionLeader::send(const MappedDevice& device) {
  auto& cmd = command_.sample();
  transport::copy_joints(device.q_cmd, config_.joints, cmd.q_des_rad());
  transport::copy_joints(device.dq_cmd, config_.joints, cmd.dq_des_radps());
  command_.publish();
}

bool PositionPositionLeader::feedback(const MappedDevice& device, int64_t now_ns, JointVector& feedback,
                                      uint64_t& rejected) {
  if (!follower_state_.has_sample()) return false;
  const auto& st = follower_state_.latest();
  JointVector q_f{};
  JointVector dq_f{};
  if (!transport::read_joints(st.q_rad(), config_.joints, q_f) ||
      !transport::read_joints(st.dq_radps(), config_.joints, dq_f)) {
    ++rejected;
    return false;
  }
  for (size_t i = 0; i < config_.joints; ++i) {
    const double tau = config_.stiffness_nm_per_rad * (q_f[i] - device.q_cmd[i]) +
                       config_.damping_nms_per_rad * (dq_f[i] - device.dq_cmd[i]);
    // device torque for a follower-space torque: scaled like the motion, so power is preserved
    feedback[i] = config_.workspace_scale * tau;
  }
  return follower_state_.age_ns(now_ns) < static_cast<int64_t>(config_.peer_timeout_s * 1e9);
}

}  // namespace teleop::leader
