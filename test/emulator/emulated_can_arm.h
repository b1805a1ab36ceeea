#pragma once
// A follower's robot for process tests on a host without CAN (`hardware: canopen_emulated`): the
// follower's CANopen master (robot::CanopenHardware, as `hardware: canopen` builds it) and the
// emulated CiA 402 drives turning the MuJoCo arm (emulator::EmulatedArm), in one process on one
// virtual bus per `bus` of the drives; the drives and the arm advance one control period after
// every cycle's SYNC. Everything of the CAN arm but SocketCAN and a second process: the VM's
// vcan HIL has those. The master's clock is the drives' time. The section's `canopen:` keys place the drives, its `mujoco:` keys name the
// arm (without its gravity compensation: the drives carry it). The arm's contact torques and
// wrench are reported as the simulation's ground truth, as the MuJoCo backend reports them.

#include <memory>
#include <string>
#include <vector>

#include "canopen_hardware.h"
#include "teleop/can/virtual_can_bus.h"
#include "teleop/emulator/emulated_arm.h"
#include "teleop/robot/hardware_registry.h"
#include "teleop/robot/mujoco_hardware.h"

namespace teleop::emulator::test {

class EmulatedCanArm final : public robot::RobotHardware {
 public:
  EmulatedCanArm(const robot::CanopenHardwareConfig& drives, robot::MujocoHardwareConfig plant, double period_s);

  size_t joints() const override { return master_->joints(); }
  [[nodiscard]] robot::HardwareStatus read(robot::ArmState& state) override;
  [[nodiscard]] robot::HardwareStatus write(const JointVector& tau_nm) override;
  [[nodiscard]] robot::HardwareStatus hold() override;
  bool compensates_gravity() const override { return false; }
  robot::HardwareLimits limits() const override { return master_->limits(); }
  const char* name() const override { return name_.c_str(); }
  void report_counters(std::vector<std::pair<std::string, double>>& counters) const override {
    master_->report_counters(counters);
  }

 private:
  double period_s_;
  std::string name_;
  robot::MujocoHardware plant_;
  std::vector<std::unique_ptr<can::VirtualCanBus>> buses_;
  std::vector<std::unique_ptr<can::VirtualCanEndpoint>> endpoints_;
  std::unique_ptr<EmulatedArm> emulated_;
  std::unique_ptr<robot::CanopenHardware> master_;
};

/// Registers it as `canopen_emulated`.
void add_emulated_canopen_backend(robot::HardwareRegistry& registry);

}  // namespace teleop::emulator::test
