#include "mmt.h"

#include "teleop/transport/joint_fields.h"

namespace teleop::leader {

MmtLeader::MmtLeader(const LeaderSetup& setup)
    : config_(setup.config), twin_feedback_(setup.peers.twin_feedback), device_state_(setup.device_state) {}

bool MmtLeader::feedback(const MappedDevice& /*device*/, int64_t now_ns, JointVector& feedback, uint64_t& rejected) {
  // the twin's constraint torque, in follower joint space: scaled like the motion
  JointVector tau{};
  if (!transport::read_joints(twin_feedback_.latest().tau_nm(), config_.joints, tau)) {
    if (twin_feedback_.has_sample()) ++rejected;
    return false;
  }
  for (size_t i = 0; i < config_.joints; ++i) feedback[i] = config_.workspace_scale * tau[i];
  return twin_feedback_.age_ns(now_ns) < static_cast<int64_t>(config_.peer_timeout_s * 1e9);
}

}  // namespace teleop::leader
