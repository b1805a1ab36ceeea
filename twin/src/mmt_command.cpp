#include "mmt_command.h"

#include "teleop/transport/joint_fields.h"

namespace teleop::twin {

MmtCommand::MmtCommand(transport::Participant& participant, const transport::TopicSpec<msg::JointCommand>& topic,
                       const std::string& source, const char* arm, size_t joints, double stiffness_nm_per_rad,
                       double damping_nms_per_rad)
    : joints_(joints), pub_(participant, topic, source) {
  auto& cmd = pub_.sample();
  cmd.robot("follower");
  cmd.arm(arm);
  cmd.mode().assign(joints_, msg::CONTROL_JOINT_IMPEDANCE);
  transport::presize(joints_, cmd.q_des_rad(), cmd.dq_des_radps(), cmd.tau_ff_nm());
  cmd.stiffness_nm_per_rad().assign(joints_, stiffness_nm_per_rad);
  cmd.damping_nms_per_rad().assign(joints_, damping_nms_per_rad);
}

void MmtCommand::publish(const JointVector& q_rad, const JointVector& dq_radps, const JointVector& contact_torque_nm) {
  auto& cmd = pub_.sample();
  transport::copy_joints(q_rad, joints_, cmd.q_des_rad());
  transport::copy_joints(dq_radps, joints_, cmd.dq_des_radps());
  for (size_t i = 0; i < joints_; ++i) cmd.tau_ff_nm()[i] = -contact_torque_nm[i];
  pub_.publish();
}

}  // namespace teleop::twin
