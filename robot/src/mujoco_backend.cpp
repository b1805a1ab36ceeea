#include "teleop/robot/mujoco_backend.h"

#include <stdexcept>

#include "teleop/common/joint_config.h"
#include "teleop/sim/model_config.h"

namespace teleop::robot {

std::unique_ptr<RobotHardware> MujocoHardwareSpec::make(double period_s) const {
  MujocoHardwareConfig config = config_;
  config.period_s = period_s;
  return std::make_unique<MujocoHardware>(config);
}

const MujocoHardwareConfig& mujoco_config(const HardwareSpec& spec) {
  const auto* mujoco = dynamic_cast<const MujocoHardwareSpec*>(&spec);
  if (mujoco == nullptr) throw std::invalid_argument(std::string("not a simulated robot: ") + spec.backend());
  return mujoco->config();
}

std::shared_ptr<const MujocoHardwareSpec> parse_mujoco_hardware(const ConfigNode& section) {
  const ConfigNode mujoco = section.child("mujoco");
  MujocoHardwareConfig config;
  config.model_path = sim::get_model_path(mujoco, "model");
  config.keyframe = mujoco.get_string("keyframe", "");
  if (const auto real = mujoco.optional_child("real_robot")) config.real_robot = sim::read_real_robot(*real);
  config.gravity_compensated = mujoco.get_bool("gravity_compensated", true);
  if (const auto payload = mujoco.optional_child("payload")) {
    SimulatedPayload p;
    p.mass_kg = payload->get_double("mass_kg", Range{0.001, 100});
    p.com_m = read_vector3(*payload, "com_m", Range{-1, 1}, p.com_m);
    p.site = payload->get_string("site", config.ee_site);
    config.payload = p;
  }
  return std::make_shared<const MujocoHardwareSpec>(config);
}

void add_mujoco_backend(HardwareRegistry& registry) {
  registry.add("mujoco", [](const ConfigNode& section) { return parse_mujoco_hardware(section); });
}

const HardwareRegistry& simulated_hardware() {
  static const HardwareRegistry registry = [] {
    HardwareRegistry r;
    add_mujoco_backend(r);
    return r;
  }();
  return registry;
}

}  // namespace teleop::robot
