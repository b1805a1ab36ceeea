#pragma once
// The follower's measured pose in the twin's model: the twin's own copy of the arm (a second
// mjData on the twin's mjModel, so the simulation's state is untouched) put at the follower's
// joint angles, and the signed distance of the follower's contact geometry (the probe) from an
// environment geom there. Construction allocates and throws; gap_m() does not.

#include <mujoco/mujoco.h>

#include <memory>
#include <string>

#include "teleop/common/joint_model.h"
#include "teleop/sim/actuated_joints.h"
#include "teleop/twin/pair_observer.h"

namespace teleop::twin {

class RemoteContactProbe {
 public:
  /// `probe`: "geom:NAME" or "body:NAME"; `geom`: the environment geom's name. Throws
  /// std::runtime_error naming `model_name` and the element when one does not exist.
  RemoteContactProbe(const mjModel* m, const std::string& probe, const std::string& geom, const std::string& model_name);

  /// The probe's signed distance from the geom with the driven joints at `q_rad` (the rest at the
  /// model's reference pose) [m], negative when it is behind the geom's surface; capped at
  /// `range_m`. Uses the geom where the model has it now. Real-time safe.
  double gap_m(const mjModel* m, const JointVector& q_rad, double range_m);

  /// Id of the environment geom.
  int geom() const { return geom_; }

 private:
  struct DataDeleter {
    void operator()(mjData* d) const noexcept { mj_deleteData(d); }
  };

  int geom_;
  sim::ActuatedJoints joints_;
  PairObserver pair_;
  std::unique_ptr<mjData, DataDeleter> data_;
};

}  // namespace teleop::twin
