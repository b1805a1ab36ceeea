#include "teleop/twin/twin_scene.h"

namespace teleop::twin {
namespace {

TwinModelConfig at_loop_rate(TwinModelConfig model, double rate_hz) {
  model.period_s = 1.0 / rate_hz;
  return model;
}

}  // namespace

TwinScene::TwinScene(const TwinModelConfig& model, runtime::NodeContext& context)
    : sim_(at_loop_rate(model, context.node.rate_hz)),
      observations_(sim_, context.participant, context.node.name),
      // no arm pulled anywhere before its robot is heard: every target at the start pose
      targets_(sim_.q_rad()) {}

void TwinScene::step() {
  sim_.step_coupled(targets_);
  observations_.publish(sim_);
}

}  // namespace teleop::twin
