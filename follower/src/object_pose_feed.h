#pragma once
// The remote site's measurement of its objects for the twin (model-mediated teleoperation,
// docs/twin.md "Object correction"): the pose and velocity of each tracked body of the shared
// scene, on teleop/follower/object_pose/<body>, at the rate of a tracking system. Here the
// simulation is the measurement; beside a real robot a motion-capture or vision tracker publishes
// the same samples. A member of the follower's ArmGroup without a name: it drives nothing.
// Construction allocates and throws; cycle() does not.

#include <memory>
#include <string>
#include <vector>

#include <teleop/msg/twin.h>

#include "teleop/follower/follower_config.h"
#include "teleop/robot/mujoco_scene.h"
#include "teleop/runtime/node_logic.h"
#include "teleop/runtime/node_runner.h"
#include "teleop/sim/body_state.h"
#include "teleop/transport/publication.h"

namespace teleop::follower {

/// Writes a body's measured state into the pose and twist of `sample`.
void write_object_pose(const sim::BodyState& state, msg::ObjectPose& sample);

class ObjectPoseFeed final : public runtime::NodeLogic {
 public:
  /// Throws std::out_of_range naming a body the scene lacks.
  ObjectPoseFeed(const ObjectPoseFeedConfig& config, std::shared_ptr<const robot::MujocoScene> scene,
                 runtime::NodeContext& context);

  void cycle(const CycleTick& tick) override;
  msg::NodeState state() const override { return msg::STATE_RUNNING; }
  void active_faults(std::vector<uint32_t>&) const override {}
  void fill_report(runtime::NodeReport& report) const override;

 private:
  struct Tracked {
    int body;
    std::unique_ptr<transport::Publication<msg::ObjectPose>> publication;
  };

  std::shared_ptr<const robot::MujocoScene> scene_;
  std::vector<Tracked> tracked_;
  uint64_t every_cycles_ = 1;
};

}  // namespace teleop::follower
