#pragma once
// The twin's side of MMT's object update: one subscription to teleop/follower/object_pose/<body>
// per corrected body of the twin's scene, each feeding its ObjectCorrection, whose wrench goes
// into MuJoCo's applied forces on that body before every step. Setup allocates and throws (a
// body the model lacks is named); apply() is real-time safe.

#include <teleop/msg/twin.h>

#include <memory>
#include <string>
#include <vector>

#include "teleop/runtime/node_report.h"
#include "teleop/sim/mujoco_model.h"
#include "teleop/transport/participant.h"
#include "teleop/transport/subscription.h"
#include "object_correction.h"

namespace teleop::twin {

/// The state a sample tells (pose and twist; the header and name are the caller's).
sim::BodyState read_object_pose(const msg::ObjectPose& sample);

class ObjectTracking {
 public:
  ObjectTracking(const ObjectCorrectionConfig& config, const sim::MujocoModel& sim, transport::Participant& participant);

  /// Takes what arrived since the last call and writes each body's correction wrench into
  /// `sim`'s applied forces (mjData::xfrc_applied), for the next step. Call between steps.
  void apply(sim::MujocoModel& sim);

  void fill_report(runtime::NodeReport& report) const;
  /// object_<body>_error_m and object_<body>_force_n per body.
  void trace_columns(std::vector<std::string>& columns) const;
  /// Writes the trace_columns() values; returns the position after them.
  double* trace_row(double* row) const;

 private:
  struct Tracked {
    std::string body_name;
    int body;
    std::unique_ptr<transport::Subscription<msg::ObjectPose>> subscription;
    ObjectCorrection correction;
    uint64_t wrong_body = 0;
  };

  void take_measurement(Tracked& t, double now_s);

  std::vector<Tracked> tracked_;
};

}  // namespace teleop::twin
