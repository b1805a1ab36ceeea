#pragma once
// teleop_hand_emulator --sim-log FILE: the MuJoCo hand's state as CSV, one row per interval, so
// that a test (or a person) can see what the simulation did while a master drove it over CAN:
//   t_s, object_x_m, object_y_m, object_z_m, object_supported, object_contacts, object_links,
//   object_force_n, the 20 joint angles q_<joint> [rad] (kHandJointNames order), the 9 motor
//   torques tau_<motor> [N m] (averaged over the last step)
// The object columns are empty when the model has none. Each row is flushed (a reader follows
// the file while the emulator runs).

#include <cstdio>
#include <memory>
#include <string>

#include "teleop/hand/grasp_object.h"
#include "teleop/hand/mujoco_drive_plants.h"

namespace teleop::hand::emulator {

class SimLog {
 public:
  /// Opens (truncates) `path` and writes the header. Throws std::runtime_error naming the file.
  SimLog(const std::string& path, double interval_s);

  /// Writes a row when at least the interval has passed since the last one.
  void sample(double t_s, const MujocoDrivePlants& plants, const GraspObject* object);

 private:
  struct Closer {
    void operator()(std::FILE* f) const { std::fclose(f); }
  };
  std::unique_ptr<std::FILE, Closer> file_;
  double interval_s_;
  double next_s_ = 0.0;
};

}  // namespace teleop::hand::emulator
