#include "emulated_can_arm.h"

#include <algorithm>
#include <cmath>

#include "teleop/robot/canopen_backend.h"
#include "teleop/robot/mujoco_backend.h"

namespace teleop::emulator::test {
namespace {

// the arm steps by at most 1 ms whatever the master's period, as teleop_arm_emulator's does
double plant_step_s(double period_s) { return std::min(period_s, 1e-3); }

robot::MujocoHardwareConfig without_gravity_compensation(robot::MujocoHardwareConfig plant, double period_s) {
  plant.gravity_compensated = false;
  plant.period_s = plant_step_s(period_s);
  return plant;
}

class EmulatedCanArmSpec final : public robot::HardwareSpec {
 public:
  EmulatedCanArmSpec(robot::CanopenHardwareConfig drives, robot::MujocoHardwareConfig plant)
      : drives_(std::move(drives)), plant_(std::move(plant)) {}
  const char* backend() const override { return "canopen_emulated"; }
  std::unique_ptr<robot::RobotHardware> make(double period_s) const override {
    return std::make_unique<EmulatedCanArm>(drives_, plant_, period_s);
  }

 private:
  robot::CanopenHardwareConfig drives_;
  robot::MujocoHardwareConfig plant_;
};

}  // namespace

EmulatedCanArm::EmulatedCanArm(const robot::CanopenHardwareConfig& drives, robot::MujocoHardwareConfig plant,
                               double period_s)
    : period_s_(period_s), plant_(without_gravity_compensation(std::move(plant), period_s)) {
  const std::vector<std::string> interfaces = robot::CanopenHardware::interfaces(drives);
  std::vector<can::CanBus*> masters;
  std::vector<can::CanBus*> drive_ends;
  for (size_t b = 0; b < interfaces.size(); ++b) {
    buses_.push_back(std::make_unique<can::VirtualCanBus>());
    endpoints_.push_back(buses_.back()->open("master"));
    masters.push_back(endpoints_.back().get());
  }
  for (const robot::CanopenJointConfig& j : drives.joints) {
    const size_t b = static_cast<size_t>(std::find(interfaces.begin(), interfaces.end(), j.bus) - interfaces.begin());
    endpoints_.push_back(buses_[b]->open("drive " + std::to_string(j.node)));
    drive_ends.push_back(endpoints_.back().get());
  }
  emulated_ = std::make_unique<EmulatedArm>(plant_, plant_step_s(period_s), drives, drive_ends);
  emulated_->step(period_s);  // powered on
  robot::SdoWait wait;
  wait.poll = std::chrono::nanoseconds(static_cast<int64_t>(period_s * 1e9));
  wait.pump = [this] { emulated_->step(period_s_); };
  // the master's clock is the emulated drives' time: in one process they advance only when the
  // master's cycle steps them, however long the follower takes between two (its start)
  master_ = std::make_unique<robot::CanopenHardware>(drives, period_s, masters, wait, [this] {
    return static_cast<int64_t>(std::llround(emulated_->drives().time_s() * 1e9));
  });
  name_ = std::string("canopen_emulated:") + (master_->name() + std::string("canopen:").size());
}

robot::HardwareStatus EmulatedCanArm::read(robot::ArmState& state) {
  const robot::HardwareStatus status = master_->read(state);
  // the simulation's contact, as ground truth for the analyses (the drives measure none)
  const robot::ArmState& truth = emulated_->plant().state();
  state.tau_ext_nm = truth.tau_ext_nm;
  state.force_ext_n = truth.force_ext_n;
  state.torque_ext_nm = truth.torque_ext_nm;
  return status;
}

robot::HardwareStatus EmulatedCanArm::write(const JointVector& tau_nm) {
  const robot::HardwareStatus status = master_->write(tau_nm);
  emulated_->step(period_s_);
  return status;
}

robot::HardwareStatus EmulatedCanArm::hold() {
  const robot::HardwareStatus status = master_->hold();
  emulated_->step(period_s_);
  return status;
}

void add_emulated_canopen_backend(robot::HardwareRegistry& registry) {
  registry.add("canopen_emulated", [](const ConfigNode& section) -> std::shared_ptr<const robot::HardwareSpec> {
    const auto drives = robot::parse_canopen_hardware(section);
    const auto plant = robot::parse_mujoco_hardware(section);
    return std::make_shared<const EmulatedCanArmSpec>(drives->config(), plant->config());
  });
}

}  // namespace teleop::emulator::test
