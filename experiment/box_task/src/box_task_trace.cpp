#include "teleop/box_task/box_task_trace.h"

namespace teleop::box_task {

BoxTaskTrace::BoxTaskTrace(std::shared_ptr<const robot::MujocoScene> scene)
    : scene_(std::move(scene)), probe_(scene_->simulation().model()) {}

void BoxTaskTrace::trace_columns(std::vector<std::string>& columns) const {
  // t_s is the trace's own first column
  for (size_t i = 1; i < box_task::kBoxTaskColumns.size(); ++i) columns.emplace_back(box_task::kBoxTaskColumns[i]);
}

void BoxTaskTrace::trace_row(double* row) const {
  const box_task::BoxTaskSample s = probe_.sample(scene_->simulation().model(), scene_->simulation().data());
  for (const Eigen::Vector3d* p : {&s.box_m, &s.left_m, &s.right_m}) {
    for (int k = 0; k < 3; ++k) *row++ = (*p)[k];
  }
  *row++ = s.left_squeeze_n;
  *row++ = s.right_squeeze_n;
  *row++ = s.support_n;
  *row = s.arm_collision_n;
}

namespace {

// linked into an executable, the probe is there to be asked for (robot/scene_probes.h)
const bool kRegistered = [] {
  add_box_task_probe(robot::linked_probes());
  return true;
}();

}  // namespace

void add_box_task_probe(robot::SceneProbes& probes) {
  probes.add("box_task", [](std::shared_ptr<const robot::MujocoScene> scene) -> std::unique_ptr<runtime::NodeLogic> {
    return std::make_unique<BoxTaskTrace>(std::move(scene));
  });
}

}  // namespace teleop::box_task
