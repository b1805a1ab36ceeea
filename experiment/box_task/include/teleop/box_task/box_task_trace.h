#pragma once
// The box task's probe (docs/box_task.md): the box, the flanges, the squeeze and support forces,
// read from the follower's simulated scene every cycle by box_task::BoxTaskProbe, into its trace as
// columns named as box_task::kBoxTaskColumns; the task's metrics are computed from them afterwards.
// The follower executable registers it as `box_task` (robot/scene_probes.h); an experiment asks
// for it with `node.probes: [box_task]`. It drives nothing.

#include <memory>

#include "teleop/robot/mujoco_scene.h"
#include "teleop/robot/scene_probes.h"
#include "teleop/runtime/node_logic.h"
#include "teleop/box_task/box_task_probe.h"

namespace teleop::box_task {

class BoxTaskTrace final : public runtime::NodeLogic {
 public:
  /// Throws std::invalid_argument naming what the scene lacks (the box, an arm's site).
  explicit BoxTaskTrace(std::shared_ptr<const robot::MujocoScene> scene);

  void cycle(const CycleTick&) override {}
  msg::NodeState state() const override { return msg::STATE_RUNNING; }
  void active_faults(std::vector<uint32_t>&) const override {}
  void fill_report(runtime::NodeReport&) const override {}
  void trace_columns(std::vector<std::string>& columns) const override;
  void trace_row(double* row) const override;

 private:
  std::shared_ptr<const robot::MujocoScene> scene_;
  box_task::BoxTaskProbe probe_;
};

/// Registers the probe as `box_task`.
void add_box_task_probe(robot::SceneProbes& probes);

}  // namespace teleop::box_task
