#pragma once
// The simulated robot as a hardware backend (`hardware: mujoco`): the arm of a MuJoCo scene
// (config/models), configured by the section's `mujoco:` keys.

#include <memory>

#include "teleop/common/config.h"
#include "teleop/robot/hardware_registry.h"
#include "teleop/robot/mujoco_hardware.h"

namespace teleop::robot {

class MujocoHardwareSpec final : public HardwareSpec {
 public:
  explicit MujocoHardwareSpec(MujocoHardwareConfig config) : config_(std::move(config)) {}
  const char* backend() const override { return "mujoco"; }
  /// The scene's only arm, stepped by its own write().
  std::unique_ptr<RobotHardware> make(double period_s) const override;
  /// Its settings (the shared scene of a multi-arm robot is built from them).
  const MujocoHardwareConfig& config() const { return config_; }

 private:
  MujocoHardwareConfig config_;
};

/// The settings of `spec`, a simulation's (throws std::invalid_argument for another backend).
const MujocoHardwareConfig& mujoco_config(const HardwareSpec& spec);

/// Reads `section.mujoco` (model: the scene's MJCF, loaded once here; keyframe; real_robot: a
/// perturbed arm with noisy sensors instead of the model, sim/plant_perturbation.h).
std::shared_ptr<const MujocoHardwareSpec> parse_mujoco_hardware(const ConfigNode& section);

/// Registers the simulation as `mujoco`.
void add_mujoco_backend(HardwareRegistry& registry);

/// A registry of the backends every build has (the simulation): what the node executables and
/// tests start from.
const HardwareRegistry& simulated_hardware();

}  // namespace teleop::robot
