#include "object_pose_feed.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "teleop/transport/joint_fields.h"
#include "teleop/transport/topics.h"

namespace teleop::follower {

void write_object_pose(const sim::BodyState& state, msg::ObjectPose& sample) {
  transport::set_vector3(sample.world_pose().position_m(), state.position_m.data());
  transport::set_quaternion(sample.world_pose().orientation(), state.orientation_wxyz.data());
  transport::set_vector3(sample.world_twist().linear_mps(), state.linear_mps.data());
  transport::set_vector3(sample.world_twist().angular_radps(), state.angular_radps.data());
}

ObjectPoseFeed::ObjectPoseFeed(const ObjectPoseFeedConfig& config, std::shared_ptr<const robot::MujocoScene> scene,
                               runtime::NodeContext& context)
    : scene_(std::move(scene)),
      every_cycles_(static_cast<uint64_t>(std::max(1.0, std::round(context.node.rate_hz / config.rate_hz)))) {
  for (const std::string& name : config.bodies) {
    const std::string topic = transport::topics::kFollowerObjectPosePrefix + name;
    Tracked t{scene_->simulation().body_id(name),
              std::make_unique<transport::Publication<msg::ObjectPose>>(
                  context.participant, transport::TopicSpec<msg::ObjectPose>{topic.c_str(), transport::QosPreset::kStream},
                  context.node.name)};
    t.publication->sample().body(name);
    tracked_.push_back(std::move(t));
  }
}

void ObjectPoseFeed::cycle(const CycleTick& tick) {
  if (tick.index % every_cycles_ != 0) return;
  const sim::MujocoModel& sim = scene_->simulation();
  for (Tracked& t : tracked_) {
    write_object_pose(sim::body_state(sim.model(), sim.data(), t.body), t.publication->sample());
    t.publication->publish();
  }
}

void ObjectPoseFeed::fill_report(runtime::NodeReport& report) const {
  for (const Tracked& t : tracked_) report.add(*t.publication);
}

}  // namespace teleop::follower
