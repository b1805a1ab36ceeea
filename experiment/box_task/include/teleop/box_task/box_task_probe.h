#pragma once
// Reads a BoxTaskSample from a simulation of scene_box_shelf.xml (or any scene with a body "box",
// the two-arm body's "left_"/"right_" arms and static environment geoms), and the shelf region the
// box must end in. Construction looks names up and throws; sample() does not allocate.

#include <mujoco/mujoco.h>

#include <vector>

#include "teleop/box_task/box_task_metrics.h"

namespace teleop::box_task {

class BoxTaskProbe {
 public:
  /// Throws std::invalid_argument naming the element when the model lacks the box body, an
  /// ee site ("left_ee_site", "right_ee_site") or an arm's base body ("left_link0", "right_link0").
  explicit BoxTaskProbe(const mjModel* scene);

  /// The task's quantities in the state of `d` (after mj_step or mj_forward): positions, and
  /// normal contact forces summed over the active contacts by the kind of their two geoms.
  BoxTaskSample sample(const mjModel* m, const mjData* d) const;

 private:
  enum class Kind : unsigned char { kRobotBody, kLeftArm, kRightArm, kBox, kEnvironment };

  std::vector<Kind> kind_;  // per geom
  int box_body_;
  int left_site_;
  int right_site_;
};

/// The region of the box centre inside the shelf compartment of `scene` (geoms "shelf_floor",
/// "shelf_ceiling", "shelf_back"; box geom "box"): the whole box over the floor in x, in front of
/// the back wall, centre over the floor in y, between floor and ceiling in z (with `tolerance_m`
/// for resting on the floor). Throws std::invalid_argument naming a missing geom.
BoxRegion shelf_region(const mjModel* scene, double tolerance_m = 0.005);

}  // namespace teleop::box_task
