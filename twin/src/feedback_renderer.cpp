#include "feedback_renderer.h"

#include <algorithm>
#include <cmath>

#include "teleop/transport/joint_fields.h"

namespace teleop::twin {

FeedbackRenderer::FeedbackRenderer(transport::Participant& participant,
                                   const transport::TopicSpec<msg::JointTorque>& topic, const std::string& source,
                                   const char* robot, const char* arm, size_t joints, const FeedbackSettings& settings)
    : joints_(joints),
      gain_(settings.gain),
      filter_(settings.cutoff_hz, settings.rate_hz),
      pub_(participant, topic, source) {
  pub_.sample().robot(robot);
  pub_.sample().arm(arm);
  transport::presize(joints_, pub_.sample().tau_nm());
}

void FeedbackRenderer::render(const JointVector& constraint_nm, bool coupled_fresh) {
  contact_torque_nm_ = filter_.apply(constraint_nm, joints_);
  for (size_t i = 0; i < joints_; ++i) {
    feedback_nm_[i] = coupled_fresh ? gain_ * contact_torque_nm_[i] : 0.0;
    peak_feedback_nm_ = std::max(peak_feedback_nm_, std::abs(feedback_nm_[i]));
  }
  transport::copy_joints(feedback_nm_, joints_, pub_.sample().tau_nm());
  pub_.publish();
}

}  // namespace teleop::twin
