#pragma once
// The follower robot: validates the leader's joint commands, runs a joint impedance law on its
// (here simulated) joints, watches for silence, and publishes its state and the wrench it feels.

#include <teleop/msg/arm.h>

#include "teleop/common/config.h"
#include "teleop/common/joint_model.h"
#include "teleop/follower/command_validator.h"
#include "teleop/follower/mujoco_hardware.h"
#include "teleop/follower/robot_hardware.h"
#include "teleop/runtime/node_runner.h"
#include "teleop/transport/publication.h"
#include "teleop/transport/subscription.h"

namespace teleop::follower {

struct FollowerConfig {
  size_t joints = 7;
  /// Which robot: the simple joint model, or a MuJoCo simulation of the arm.
  enum class Hardware { kSimple, kMujoco } hardware = Hardware::kSimple;
  JointModelParams model;
  MujocoHardwareConfig mujoco;
  JointVector home_rad{};
  JointLimits limits;
  /// No valid command for this long: hold the current pose (watchdog).
  double command_timeout_s = 0.02;
  /// Impedance used to hold the pose in the safe state.
  double hold_stiffness_nm_per_rad = 200.0;
  double hold_damping_nms_per_rad = 20.0;
  /// Distance from joint 0 to the contact point, to express the contact torque as a force [m].
  double wrench_lever_m = 0.5;
};

class FollowerNode final : public runtime::NodeLogic {
 public:
  /// Reads the `follower:` section.
  static FollowerConfig parse_config(const ConfigNode& root);

  FollowerNode(const FollowerConfig& config, runtime::NodeContext& context);

  void cycle(const CycleTick& tick) override;
  msg::NodeState state() const override { return state_; }
  void active_faults(std::vector<uint32_t>& faults) const override;
  void fill_report(runtime::NodeReport& report) const override;

 private:
  void take_command(int64_t now_ns);
  void run_watchdog(int64_t now_ns);
  void compute_torque();
  void publish_state();

  FollowerConfig config_;
  std::unique_ptr<RobotHardware> hardware_;
  ArmState arm_{};
  CommandValidator validator_;
  transport::Subscription<msg::JointCommand> command_;
  transport::Publication<msg::JointState> state_pub_;
  transport::Publication<msg::WrenchStamped> wrench_pub_;
  msg::NodeState state_ = msg::STATE_STARTING;
  ValidCommand active_{};
  int64_t last_valid_command_ns_ = 0;
  bool have_command_ = false;
  JointVector tau_nm_{};
  uint64_t watchdog_trips_ = 0;
  uint64_t torque_saturations_ = 0;
  uint64_t hardware_faults_ = 0;
  double peak_external_force_n_ = 0.0;
};

}  // namespace teleop::follower
