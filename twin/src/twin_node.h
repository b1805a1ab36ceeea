#pragma once
// The digital twin node (docs/twin.md): a MuJoCo simulation of the robot (TwinSimulation) run in
// one of three modes – real-time coupled to a robot's joint state with the constraint torque
// rendered back as haptic feedback (PARTI eq. 2/3), lock-step with an external controller
// process (thesis §3.4), or hardware in the loop (PARTI §2.2) – publishing its state, the contact
// wrench of each configured contact pair and the distances of the configured geometry pairs.

#include <memory>
#include <optional>
#include <vector>

#include <teleop/msg/arm.h>
#include <teleop/msg/twin.h>

#include "teleop/runtime/node_runner.h"
#include "teleop/transport/publication.h"
#include "teleop/transport/subscription.h"
#include "coupled_robot.h"
#include "teleop/common/stall_watch.h"
#include "feedback_renderer.h"
#include "hil_controller.h"
#include "lockstep_link.h"
#include "mmt_command.h"
#include "model_correction.h"
#include "twin_config.h"
#include "twin_observations.h"
#include "teleop/twin/twin_simulation.h"

namespace teleop::twin {

class TwinNode final : public runtime::NodeLogic {
 public:
  /// Reads the `twin:` section.
  static TwinConfig parse_config(const ConfigNode& root) { return parse_twin_config(root); }

  /// Loads the model (throws std::runtime_error naming the file) and creates the endpoints of the mode.
  TwinNode(const TwinConfig& config, runtime::NodeContext& context);

  void cycle(const CycleTick& tick) override;
  msg::NodeState state() const override { return state_; }
  void active_faults(std::vector<uint32_t>& faults) const override;
  void fill_report(runtime::NodeReport& report) const override;
  void trace_columns(std::vector<std::string>& columns) const override;
  void trace_row(double* row) const override;

  const TwinSimulation& simulation() const { return sim_; }
  /// MMT's model update from the follower's measurements (absent unless configured).
  const std::optional<ModelCorrection>& model_correction() const { return correction_; }

 private:
  void cycle_coupled(const CycleTick& tick);
  void cycle_lockstep();
  void cycle_hil(const CycleTick& tick);
  void publish_state();
  uint64_t rejected_samples() const { return rejected_samples_ + (coupled_ ? coupled_->rejected() : 0); }
  void record_trajectory();
  void write_trajectory() const;

  TwinConfig config_;
  TwinSimulation sim_;
  size_t joints_;
  std::optional<CoupledRobot> coupled_;                                // real-time mode
  std::optional<transport::Subscription<msg::JointState>> measured_;  // hardware in the loop
  transport::Publication<msg::JointState> state_pub_;
  FeedbackRenderer feedback_;
  TwinObservations observations_;
  std::optional<LockstepLink> lockstep_;
  std::optional<HilController> hil_;
  std::optional<transport::Publication<msg::JointCommand>> hil_command_pub_;
  std::optional<MmtCommand> mmt_command_;
  std::optional<ModelCorrection> correction_;

  msg::NodeState state_ = msg::STATE_STARTING;
  JointVector q_coupled_{};
  JointVector dq_coupled_{};
  JointVector tau_cmd_{};
  JointVector damping_cmd_{};
  double hil_start_s_ = 0.0;
  double goal_error_rad_ = -1.0;
  uint64_t rejected_samples_ = 0;
  uint64_t stalls_ = 0;
  // real-time mode: a stall of our own loop holds for a cycle (common/stall_watch.h)
  StallWatch stall_watch_;
  std::vector<double> trajectory_;
};

}  // namespace teleop::twin
