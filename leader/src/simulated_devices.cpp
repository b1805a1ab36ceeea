#include "teleop/leader/simulated_devices.h"

#include <utility>

#include "joint_trajectory.h"
#include "replay_device.h"
#include "scripted_device.h"
#include "simulated_haptic_arm.h"
#include "teleop/common/joint_config.h"
#include "teleop/sim/model_config.h"

namespace teleop::leader {
namespace {

class ScriptedSpec final : public DeviceSpec {
 public:
  const char* device() const override { return "scripted"; }
  std::unique_ptr<LeaderDevice> make(const DeviceSetup& setup) const override {
    return std::make_unique<ScriptedDevice>(setup.joints);
  }
};

class HapticArmSpec final : public DeviceSpec {
 public:
  explicit HapticArmSpec(HapticArmConfig config) : config_(std::move(config)) {}
  const char* device() const override { return "haptic_arm"; }
  std::unique_ptr<LeaderDevice> make(const DeviceSetup& setup) const override {
    HapticArmConfig arm = config_;
    arm.model.period_s = setup.period_s;
    arm.start_rad = setup.home_rad;  // without a keyframe the device starts where the follower does
    // the hand of a two-handed station is mounted like the robot's arm: one model for both
    if (arm.model.model_path.empty()) arm.model.model_path = setup.arm_model;
    return std::make_unique<SimulatedHapticArm>(arm);
  }

 private:
  HapticArmConfig config_;
};

class ReplaySpec final : public DeviceSpec {
 public:
  explicit ReplaySpec(std::shared_ptr<const JointTrajectory> recording) : recording_(std::move(recording)) {}
  const char* device() const override { return "replay"; }
  std::unique_ptr<LeaderDevice> make(const DeviceSetup& setup) const override {
    return std::make_unique<ReplayDevice>(*recording_, setup.period_s);
  }

 private:
  std::shared_ptr<const JointTrajectory> recording_;
};

std::shared_ptr<const DeviceSpec> parse_haptic_arm(const ConfigNode& s) {
  const auto arm = s.optional_child("haptic_arm");
  if (!arm) throw s.error("haptic_arm", "device: haptic_arm needs a haptic_arm section with the model file");
  HapticArmConfig c;
  // a two-handed station names each hand's model in leader.arms (DeviceSetup::arm_model)
  if (!s.has("arms")) c.model.model_path = sim::get_model_path(*arm, "model");
  c.model.keyframe = arm->get_string("keyframe", "");
  c.hand_stiffness_nm_per_rad =
      arm->get_double("hand_stiffness_nm_per_rad", Range{0, 1e4}, c.hand_stiffness_nm_per_rad);
  c.hand_damping_nms_per_rad = arm->get_double("hand_damping_nms_per_rad", Range{0, 1e3}, c.hand_damping_nms_per_rad);
  return std::make_shared<HapticArmSpec>(c);
}

std::shared_ptr<const DeviceSpec> parse_replay(const ConfigNode& s) {
  // loaded here, before the node joins the network: a bad recording is a configuration error
  const ConfigNode replay = s.child("replay");
  return std::make_shared<ReplaySpec>(std::make_shared<const JointTrajectory>(
      JointTrajectory::load_csv(replay.get_path("file"), read_joint_count(s), replay.get_string("columns", "q_dev_"))));
}

}  // namespace

std::shared_ptr<const DeviceSpec> scripted_device_spec() {
  static const auto spec = std::make_shared<const ScriptedSpec>();
  return spec;
}

void add_simulated_devices(DeviceRegistry& registry) {
  registry.add("scripted", [](const ConfigNode&) { return scripted_device_spec(); });
  registry.add("haptic_arm", parse_haptic_arm);
  registry.add("replay", parse_replay);
}

const DeviceRegistry& simulated_devices() {
  static const DeviceRegistry registry = [] {
    DeviceRegistry r;
    add_simulated_devices(r);
    return r;
  }();
  return registry;
}

}  // namespace teleop::leader
