#pragma once
// The simulated world the follower's arms live in: one MuJoCo model with every arm, object and
// obstacle of the scene. One arm (scene_wall.xml) or both arms of the two-arm body with the box
// between them (scene_box_shelf.xml): arms that touch the same object must share one simulation.
// Each arm is a MujocoHardware view onto it; the scene advances by one control period per step().

#include <array>
#include <memory>
#include <optional>
#include <string>

#include "teleop/sim/mujoco_model.h"
#include "teleop/sim/plant_perturbation.h"

namespace teleop::robot {

/// A tool on an arm's flange that the robot's own gravity compensation does not know, as a tool
/// changed without telling the robot (docs/calibration.md): a point mass at `com_m` in the frame
/// of `site`, added to the simulated arm only.
struct SimulatedPayload {
  double mass_kg = 0.0;
  std::array<double, 3> com_m{};
  std::string site = "ee_site";
};

struct MujocoSceneConfig {
  /// MJCF file of the scene.
  std::string model_path;
  /// Keyframe to start from ("" = the model's default state).
  std::string keyframe;
  /// Control period; the model's timestep must divide it.
  double period_s = 0.001;
  /// A "real" robot instead of the model (docs/fidelity.md): the scene's arms perturbed within
  /// these bounds, their sensors noisy, drawn from its seed. The robot's own gravity compensation
  /// stays the nominal model's, as a real robot's comes from its maker's model.
  std::optional<sim::RealRobotSpec> real_robot;
  /// A payload on the flange (none: the arm as modelled).
  std::optional<SimulatedPayload> payload;
};

class MujocoScene {
 public:
  /// Loads the model (throws std::runtime_error naming the file).
  explicit MujocoScene(const MujocoSceneConfig& config);

  /// Advances the simulation by one control period. Real-time safe.
  void step();
  /// Gravity torque of every degree of freedom at the current pose, computed once per period on
  /// a second mjData at rest, so the simulation itself is not disturbed; by the nominal model
  /// when the scene is a perturbed "real" robot or carries a payload. Real-time safe.
  const mjtNum* gravity();
  /// The perturbation drawn for a "real" robot (empty otherwise).
  const sim::AppliedPerturbation& perturbation() const { return perturbation_; }
  /// The "real" robot this scene is, if it is one.
  const std::optional<sim::RealRobotSpec>& real_robot() const { return real_robot_; }
  /// Call after changing the state outside step() (setup: placing an arm).
  void state_changed();

  sim::MujocoModel& simulation() { return sim_; }
  const sim::MujocoModel& simulation() const { return sim_; }
  const std::string& file_name() const { return file_name_; }

 private:
  sim::MujocoModel sim_;
  // the nominal model a "real" robot or one with a payload compensates gravity with (null: the
  // simulated one)
  std::unique_ptr<mjModel, void (*)(mjModel*)> nominal_;
  std::unique_ptr<mjData, void (*)(mjData*)> rest_;
  std::optional<sim::RealRobotSpec> real_robot_;
  sim::AppliedPerturbation perturbation_;
  std::string file_name_;
  int substeps_ = 1;
  bool gravity_current_ = false;
};

}  // namespace teleop::robot
