#pragma once
// One arm of a multi-arm twin (twin.arms, docs/twin.md): coupled to its own robot arm (the
// leader's hand of the same name, or the follower's arm) on that arm's topics (T/<arm>,
// transport/arm_topic.h), it writes that arm's coupling target into the shared TwinScene, and
// once the scene stepped renders its own feedback (eq. 3, its own filter), publishes its own
// state and, under MMT, commands its own follower arm. A silent robot arm puts this arm alone in
// safe hold: it holds its last target, renders zero and commands nothing (the follower arm's
// watchdog holds it). Setup allocates and throws; cycle() and publish_step() do not.

#include <optional>

#include <teleop/msg/arm.h>

#include "teleop/common/error_stats.h"
#include "teleop/runtime/node_runner.h"
#include "teleop/transport/publication.h"
#include "coupled_robot.h"
#include "feedback_renderer.h"
#include "mmt_command.h"
#include "twin_config.h"
#include "twin_scene.h"

namespace teleop::twin {

class TwinArm final : public runtime::NodeLogic {
 public:
  /// The arm `config.arm`, whose joints are the scene's driven joints from `first_joint` on.
  /// `scene` must outlive it (both are members of the twin's ArmGroup).
  TwinArm(const TwinConfig& config, TwinScene& scene, size_t first_joint, runtime::NodeContext& context);

  /// Takes the coupled arm's newest joint state as this arm's target in the scene. Real-time safe.
  void cycle(const CycleTick& tick) override;
  /// After the scene stepped: feedback, state and (MMT) the follower arm's command. Real-time safe.
  void publish_step();

  msg::NodeState state() const override { return state_; }
  void active_faults(std::vector<uint32_t>& faults) const override;
  /// The arm's topics; peak_feedback_nm, rejected_samples, coupling_rmse_rad and
  /// coupling_max_error_rad (the twin arm against its coupled arm while that is fresh).
  void fill_report(runtime::NodeReport& report) const override;
  /// state, q_<i>, tau_fb_<i> (as a one-arm twin's), coupling_error_rad (largest |q_coupled - q|).
  void trace_columns(std::vector<std::string>& columns) const override;
  void trace_row(double* row) const override;

 private:
  /// This arm's part of a vector over all driven joints, from index 0.
  const JointVector& slice(const JointVector& all);

  TwinConfig config_;
  TwinScene& scene_;
  size_t first_;
  size_t joints_;
  CoupledRobot coupled_;
  transport::Publication<msg::JointState> state_pub_;
  FeedbackRenderer feedback_;
  std::optional<MmtCommand> command_;
  msg::NodeState state_ = msg::STATE_STARTING;
  bool fresh_ = false;
  JointVector slice_{};
  JointVector q_rad_{};
  JointVector dq_radps_{};
  ErrorStats coupling_;
  double coupling_error_rad_ = 0.0;
};

}  // namespace teleop::twin
