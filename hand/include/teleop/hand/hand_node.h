#pragma once
// The hand node: runs the CANopen adapter (teleop::HandAdapter) on the hand's CAN bus at
// the node's rate, takes HandCommand from DDS and publishes HandState, the 20 joint angles and
// (through the runner) NodeStatus with the faults.
//
// Start-up (constructor, before the loop): boot, configuration, enable walk and homing run to
// completion or throw with the adapter's message (e.g. the node that never booted), so a hand
// that cannot start never reports "running". In the loop: a fault drives the adapter's safe
// state (quick stop, hold), reported as STATE_SAFE_HOLD with FAULT_HARDWARE, per-motor
// HAND_FAULT_* bits and codes in HandState; a HandCommand with a rising fault_reset recovers.

#include <memory>

#include <teleop/msg/arm.h>
#include <teleop/msg/hand.h>

#include "teleop/can/can_bus.h"
#include "teleop/hand/hand_adapter.h"
#include "teleop/hand/hand_config.h"
#include "teleop/runtime/node_runner.h"
#include "teleop/transport/publication.h"
#include "teleop/transport/subscription.h"

namespace teleop::hand {

class HandNode final : public runtime::NodeLogic {
 public:
  /// Reads the `hand:` section.
  static HandNodeConfig parse_config(const ConfigNode& root) { return parse_hand_config(root); }

  /// Opens SocketCAN on config.interface, filtered to the hand's nodes.
  HandNode(const HandNodeConfig& config, runtime::NodeContext& context);
  /// On any bus (tests: a VirtualCanBus endpoint with emulated drives).
  HandNode(const HandNodeConfig& config, runtime::NodeContext& context, std::unique_ptr<can::CanBus> bus);

  void cycle(const CycleTick& tick) override;
  msg::NodeState state() const override;
  /// Engaged: the drives quick-stop and hold (the hand's disable), commands wait for the enable.
  void emergency_stop(bool engaged) override;
  void active_faults(std::vector<uint32_t>& faults) const override;
  void fill_status(msg::NodeStatus& status) const override;
  void fill_report(runtime::NodeReport& report) const override;

  const HandAdapter& adapter() const { return adapter_; }

 private:
  void start_up(int64_t period_ns);
  void take_command();
  void publish();

  HandNodeConfig config_;
  std::unique_ptr<can::CanBus> bus_;
  HandAdapter adapter_;
  transport::Subscription<msg::HandCommand> command_;
  transport::Publication<msg::HandState> state_pub_;
  transport::Publication<msg::JointState> joints_pub_;
  HandTargets targets_;
  bool command_stale_ = true;
  bool emergency_stopped_ = false;
};

}  // namespace teleop::hand
