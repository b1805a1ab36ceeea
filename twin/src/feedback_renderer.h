#pragma once
// PARTI eq. 3 for one coupled robot: lambda * lowpass(constraint torque) published on its
// feedback topic, zero while that robot is not fresh (there is nothing to render on). The
// low-passed contact torque is kept for MMT's feed-forward. Setup allocates; render() does not.

#include <string>

#include <teleop/msg/arm.h>

#include "teleop/common/lowpass.h"
#include "teleop/transport/participant.h"
#include "teleop/transport/publication.h"

namespace teleop::twin {

struct FeedbackSettings {
  /// lambda of eq. 3 and the filter's cutoff (0: unfiltered) at the loop's rate.
  double gain = 0.5;
  double cutoff_hz = 30.0;
  double rate_hz = 1000.0;
};

class FeedbackRenderer {
 public:
  /// Writes on `topic`; `robot` and `arm` label every sample.
  FeedbackRenderer(transport::Participant& participant, const transport::TopicSpec<msg::JointTorque>& topic,
                   const std::string& source, const char* robot, const char* arm, size_t joints,
                   const FeedbackSettings& settings);

  /// Filters `constraint_nm` (first `joints` values) and publishes the rendered torque. Real-time safe.
  void render(const JointVector& constraint_nm, bool coupled_fresh);

  /// The low-passed constraint torque of the last render, before lambda.
  const JointVector& contact_torque_nm() const { return contact_torque_nm_; }
  /// What the last render sent.
  const JointVector& feedback_nm() const { return feedback_nm_; }
  double peak_feedback_nm() const { return peak_feedback_nm_; }
  const transport::Publication<msg::JointTorque>& publication() const { return pub_; }

 private:
  size_t joints_;
  double gain_;
  LowPassFilter filter_;
  transport::Publication<msg::JointTorque> pub_;
  JointVector contact_torque_nm_{};
  JointVector feedback_nm_{};
  double peak_feedback_nm_ = 0.0;
};

}  // namespace teleop::twin
