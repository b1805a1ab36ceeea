#pragma once
// Model-mediated teleoperation's command to one follower arm: joint impedance towards the twin
// arm's q and dq, plus tau_ff = -(low-passed contact torque), so that the follower pushes on its
// environment as hard as the twin's environment pushes back on the twin (tracking the position
// alone, it would only touch the wall). Setup allocates; publish() does not.

#include <string>

#include <teleop/msg/arm.h>

#include "teleop/common/joint_model.h"
#include "teleop/transport/participant.h"
#include "teleop/transport/publication.h"

namespace teleop::twin {

class MmtCommand {
 public:
  /// Writes on `topic`, labelled for the follower's `arm`, with these gains on every joint.
  MmtCommand(transport::Participant& participant, const transport::TopicSpec<msg::JointCommand>& topic,
             const std::string& source, const char* arm, size_t joints, double stiffness_nm_per_rad,
             double damping_nms_per_rad);

  /// Sends the twin arm's state (first `joints` values of each vector). Real-time safe.
  void publish(const JointVector& q_rad, const JointVector& dq_radps, const JointVector& contact_torque_nm);

  const transport::Publication<msg::JointCommand>& publication() const { return pub_; }

 private:
  size_t joints_;
  transport::Publication<msg::JointCommand> pub_;
};

}  // namespace teleop::twin
