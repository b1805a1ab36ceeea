// `leader.device: robot_arm`: the robot backend and its keys read with the configuration (by the
// registry of robots the executable brings), the arm and its gravity model built when the node
// starts.
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>

#include "robot_arm_device.h"
#include "teleop/common/joint_config.h"
#include "teleop/leader/arm_devices.h"
#include "teleop/sim/model_config.h"

namespace teleop::leader {
namespace {

class RobotArmSpec final : public DeviceSpec {
 public:
  RobotArmSpec(std::shared_ptr<const robot::HardwareSpec> hardware, std::string gravity_model,
               const JointVector& max_torque_nm, const JointVector& damping_nms_per_rad)
      : hardware_(std::move(hardware)),
        gravity_model_(std::move(gravity_model)),
        max_torque_nm_(max_torque_nm),
        damping_nms_per_rad_(damping_nms_per_rad) {}
  const char* device() const override { return "robot_arm"; }
  std::unique_ptr<LeaderDevice> make(const DeviceSetup& setup) const override {
    std::unique_ptr<robot::RobotHardware> arm = hardware_->make(setup.period_s);
    std::unique_ptr<ArmKinematics> gravity;
    if (!arm->compensates_gravity()) {
      const std::string& model = gravity_model_.empty() ? setup.arm_model : gravity_model_;
      if (model.empty()) {
        throw std::runtime_error("leader.robot_arm: the " + std::string(hardware_->backend()) +
                                 " arm does not carry its own weight, and neither leader.robot_arm.gravity_model nor "
                                 "leader.arm_model names its model");
      }
      gravity = std::make_unique<ArmKinematics>(model, setup.ee_site);
    }
    return std::make_unique<RobotArmDevice>(std::move(arm), std::move(gravity), max_torque_nm_, damping_nms_per_rad_);
  }

 private:
  std::shared_ptr<const robot::HardwareSpec> hardware_;
  std::string gravity_model_;
  JointVector max_torque_nm_;
  JointVector damping_nms_per_rad_;
};

}  // namespace

void add_robot_arm_device(DeviceRegistry& registry, const robot::HardwareRegistry& robots) {
  registry.add("robot_arm", [robots](const ConfigNode& s) -> std::shared_ptr<const DeviceSpec> {
    const ConfigNode arm = s.child("robot_arm");
    std::shared_ptr<const robot::HardwareSpec> hardware = robots.parse(arm);
    const std::string gravity_model = arm.has("gravity_model") ? sim::get_model_path(arm, "gravity_model") : "";
    const size_t joints = read_joint_count(s);
    const JointVector max_torque_nm =
        read_joint_list(arm, "max_torque_nm", joints, Range{0, 1e4}, std::numeric_limits<double>::infinity());
    const JointVector damping = read_joint_list(arm, "damping_nms_per_rad", joints, Range{0, 1e3}, 0.0);
    return std::make_shared<RobotArmSpec>(std::move(hardware), gravity_model, max_torque_nm, damping);
  });
}

}  // namespace teleop::leader
