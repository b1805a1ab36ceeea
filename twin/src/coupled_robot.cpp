#include "coupled_robot.h"

#include "teleop/transport/joint_fields.h"

namespace teleop::twin {

CoupledRobot::CoupledRobot(transport::Participant& participant, const transport::TopicSpec<msg::JointState>& topic,
                           size_t joints, double peer_timeout_s, const JointVector& start_rad,
                           double rejoin_speed_radps, double cycle_s)
    : sub_(participant, topic),
      joints_(joints),
      timeout_ns_(static_cast<int64_t>(peer_timeout_s * 1e9)),
      q_rad_(start_rad),
      ramp_(joints, rejoin_speed_radps, cycle_s) {}

bool CoupledRobot::update(int64_t now_ns, msg::NodeState& state, bool stalled) {
  // what the twin was pulled to until now: where it holds
  const JointVector held = q_rad();
  if (sub_.poll() > 0 && !transport::read_joints(sub_.latest().q_rad(), joints_, q_rad_)) {
    ++rejected_;
    sub_.reject_latest(0, "wrong_size");
  }
  const bool fresh = !stalled && sub_.age_ns(now_ns) < timeout_ns_;
  if (fresh) {
    if (state != msg::STATE_RUNNING) ramp_.start(held);
    state = msg::STATE_RUNNING;
  } else if (state == msg::STATE_RUNNING) {
    state = msg::STATE_SAFE_HOLD;
    ramp_.stop();
  }
  ramp_.step(q_rad_);
  return fresh;
}

}  // namespace teleop::twin
