#pragma once
// The simulated world the follower's arms live in: one MuJoCo model with every arm, object and
// obstacle of the scene. One arm (scene_wall.xml) or both arms of the two-arm body with the box
// between them (scene_box_shelf.xml): arms that touch the same object must share one simulation.
// Each arm is a MujocoHardware view onto it; the scene advances by one control period per step().

#include <memory>
#include <string>

#include "teleop/sim/mujoco_model.h"

namespace teleop::robot {

struct MujocoSceneConfig {
  /// MJCF file of the scene.
  std::string model_path;
  /// Keyframe to start from ("" = the model's default state).
  std::string keyframe;
  /// Control period; the model's timestep must divide it.
  double period_s = 0.001;
};

class MujocoScene {
 public:
  /// Loads the model (throws std::runtime_error naming the file).
  explicit MujocoScene(const MujocoSceneConfig& config);

  /// Advances the simulation by one control period. Real-time safe.
  void step();
  /// Gravity torque of every degree of freedom at the current pose, computed once per period on
  /// a second mjData at rest, so the simulation itself is not disturbed. Real-time safe.
  const mjtNum* gravity();
  /// Call after changing the state outside step() (setup: placing an arm).
  void state_changed();

  sim::MujocoModel& simulation() { return sim_; }
  const sim::MujocoModel& simulation() const { return sim_; }
  const std::string& file_name() const { return file_name_; }

 private:
  sim::MujocoModel sim_;
  std::unique_ptr<mjData, void (*)(mjData*)> rest_;
  std::string file_name_;
  int substeps_ = 1;
  bool gravity_current_ = false;
};

}  // namespace teleop::robot
