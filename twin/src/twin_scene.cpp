#include "twin_scene.h"

namespace teleop::twin {
namespace {

TwinModelConfig at_loop_rate(TwinModelConfig model, double rate_hz) {
  model.period_s = 1.0 / rate_hz;
  return model;
}

}  // namespace

TwinScene::TwinScene(const TwinModelConfig& model, const std::optional<ObjectCorrectionConfig>& objects,
                     runtime::NodeContext& context)
    : sim_(at_loop_rate(model, context.node.rate_hz)),
      observations_(sim_, context.participant, context.node.name),
      // no arm pulled anywhere before its robot is heard: every target at the start pose
      targets_(sim_.q_rad()) {
  if (objects) objects_ = std::make_unique<ObjectTracking>(*objects, sim_.simulation(), context.participant);
}

void TwinScene::step() {
  if (objects_) objects_->apply(sim_.simulation());
  sim_.step_coupled(targets_);
  observations_.publish(sim_);
}

void TwinScene::fill_report(runtime::NodeReport& report) const {
  observations_.fill_report(report, sim_, true);
  if (objects_) objects_->fill_report(report);
}

void TwinScene::trace_columns(std::vector<std::string>& columns) const {
  observations_.trace_columns(columns);
  if (objects_) objects_->trace_columns(columns);
}

void TwinScene::trace_row(double* row) const {
  row = observations_.trace_row(row);
  if (objects_) objects_->trace_row(row);
}

}  // namespace teleop::twin
