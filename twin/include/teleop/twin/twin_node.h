#pragma once
// The digital twin: a simulated copy of the robot coupled to the leader's measured joint state
// by a joint PD law (PARTI eq. 2, tau = K (q_coupled - q_twin) - D dq_twin), so contacts act on
// it, and its constraint torque rendered back as haptic feedback (eq. 3, tau = lambda * tau_c,
// low-pass filtered). The joint model here is the simple one from common; the MuJoCo model
// replaces it behind the same node.

#include <teleop/msg/arm.h>

#include "teleop/common/config.h"
#include "teleop/common/joint_model.h"
#include "teleop/common/lowpass.h"
#include "teleop/runtime/node_runner.h"
#include "teleop/transport/publication.h"
#include "teleop/transport/subscription.h"

namespace teleop::twin {

struct TwinConfig {
  JointModelParams model;
  JointVector home_rad{};
  double coupling_stiffness_nm_per_rad = 300.0;
  double coupling_damping_nms_per_rad = 10.0;
  /// lambda of PARTI eq. 3.
  double feedback_gain = 0.5;
  double feedback_cutoff_hz = 30.0;
  /// Leader silent longer than this: stop rendering feedback.
  double peer_timeout_s = 0.1;
};

class TwinNode final : public runtime::NodeLogic {
 public:
  /// Reads the `twin:` section.
  static TwinConfig parse_config(const ConfigNode& root);

  TwinNode(const TwinConfig& config, runtime::NodeContext& context);

  void cycle(const CycleTick& tick) override;
  msg::NodeState state() const override { return state_; }
  void active_faults(std::vector<uint32_t>& faults) const override;
  void fill_report(runtime::NodeReport& report) const override;

 private:
  void couple();
  void publish(bool render_feedback);

  TwinConfig config_;
  double period_s_;
  JointModel model_;
  LowPassFilter feedback_filter_;
  transport::Subscription<msg::JointState> leader_state_;
  transport::Publication<msg::JointState> state_pub_;
  transport::Publication<msg::JointTorque> feedback_pub_;
  msg::NodeState state_ = msg::STATE_STARTING;
  JointVector q_coupled_{};
  JointVector tau_nm_{};
  JointVector feedback_nm_{};
  double peak_feedback_nm_ = 0.0;
  uint64_t rejected_samples_ = 0;
};

}  // namespace teleop::twin
