#pragma once
// The box task's quantities in the follower's trace (docs/box_task.md): the box, the flanges, the
// squeeze and support forces, read from the shared simulation every cycle by task::BoxTaskProbe,
// as columns named as task::kBoxTaskColumns. The task's metrics are computed from them
// afterwards. A member of the follower's ArmGroup without a name: it drives nothing.

#include <memory>

#include "teleop/follower/mujoco_scene.h"
#include "teleop/runtime/node_logic.h"
#include "teleop/task/box_task_probe.h"

namespace teleop::follower {

class BoxTaskTrace final : public runtime::NodeLogic {
 public:
  /// Throws std::invalid_argument naming what the scene lacks (the box, an arm's site).
  explicit BoxTaskTrace(std::shared_ptr<const MujocoScene> scene);

  void cycle(const CycleTick&) override {}
  msg::NodeState state() const override { return msg::STATE_RUNNING; }
  void active_faults(std::vector<uint32_t>&) const override {}
  void fill_report(runtime::NodeReport&) const override {}
  void trace_columns(std::vector<std::string>& columns) const override;
  void trace_row(double* row) const override;

 private:
  std::shared_ptr<const MujocoScene> scene_;
  task::BoxTaskProbe probe_;
};

}  // namespace teleop::follower
