#include "teleop/view/bus_layers.h"

#include <spdlog/fmt/fmt.h>

#include <algorithm>

#include "teleop/transport/arm_topic.h"
#include "teleop/transport/joint_fields.h"
#include "teleop/transport/topics.h"

namespace teleop::view {

// one arm's samples of one layer
struct BusLayers::ArmFeed {
  Layer layer = Layer::kFollower;
  size_t arm = 0;
  std::string topic;
  transport::Reader<msg::JointState> state;      // follower, twin
  transport::Reader<msg::JointCommand> command;  // leader
  msg::JointState state_sample;
  msg::JointCommand command_sample;
  uint64_t received = 0;
  uint64_t mismatched = 0;
  int64_t last_ns = 0;
  uint64_t last_seq = 0;
  bool posed = false;
  bool is_command() const { return layer == Layer::kLeader && topic.find("joint_command") != std::string::npos; }
};

struct BusLayers::ObjectFeed {
  size_t body = 0;
  std::string topic;
  transport::Reader<msg::ObjectPose> reader;
  msg::ObjectPose sample;
  uint64_t received = 0;
  int64_t last_ns = 0;
  uint64_t last_seq = 0;
};

struct BusLayers::WrenchFeed {
  size_t arm = 0;
  std::string topic;
  transport::Reader<msg::WrenchStamped> reader;
  msg::WrenchStamped sample;
  uint64_t received = 0;
  int64_t last_ns = 0;
  uint64_t last_seq = 0;
};

LayerChoice shown_layers(const PosedScene& scene, LayerChoice chosen) {
  for (size_t a = 0; a < scene.arm_count(); ++a) {
    if (scene.arm(a).state_topic.empty()) return chosen;
  }
  return {false, false};
}

BusLayers::BusLayers(transport::Participant& participant, const PosedScene& scene, LayerChoice choice) {
  auto add = [&](Layer layer, size_t arm, const std::string& topic) -> ArmFeed& {
    arms_.push_back(std::make_unique<ArmFeed>());
    ArmFeed& f = *arms_.back();
    f.layer = layer;
    f.arm = arm;
    f.topic = topic;
    return f;
  };
  bool arm_topics = false;
  for (size_t a = 0; a < scene.arm_count(); ++a) {
    const std::string& arm = scene.arm(a).name;
    if (!scene.arm(a).state_topic.empty()) {
      // posed by its own topic only (the hand): no twin, leader or wrench of it on the bus
      const transport::TopicSpec<msg::JointState> spec{scene.arm(a).state_topic.c_str(), transport::QosPreset::kStream};
      add(Layer::kFollower, a, spec.name).state = participant.make_reader(spec);
      continue;
    }
    arm_topics = true;
    {
      const auto topic = transport::arm_topic(transport::topics::kFollowerState, arm);
      add(Layer::kFollower, a, topic.name()).state = participant.make_reader<msg::JointState>(topic);
    }
    if (scene.ee_site(a) >= 0) {
      const auto topic = transport::arm_topic(transport::topics::kFollowerWrench, arm);
      wrenches_.push_back(std::make_unique<WrenchFeed>());
      wrenches_.back()->arm = a;
      wrenches_.back()->topic = topic.name();
      wrenches_.back()->reader = participant.make_reader<msg::WrenchStamped>(topic);
    }
    if (choice.twin) {
      const auto topic = transport::arm_topic(transport::topics::kTwinState, arm);
      add(Layer::kTwin, a, topic.name()).state = participant.make_reader<msg::JointState>(topic);
    }
    if (choice.leader) {
      // the operator's command: the leader's joint command (position-position, PFC), or the
      // device's state where the twin is commanded by it (MMT)
      const auto command = transport::arm_topic(transport::topics::kLeaderCommand, arm);
      add(Layer::kLeader, a, command.name()).command = participant.make_reader<msg::JointCommand>(command);
      const auto state = transport::arm_topic(transport::topics::kLeaderState, arm);
      add(Layer::kLeader, a, state.name()).state = participant.make_reader<msg::JointState>(state);
    }
  }
  // the follower tracks the objects of an arm's scene; the hand's object is the emulator's own
  for (size_t b = 0; arm_topics && b < scene.free_bodies().size(); ++b) {
    const std::string topic = transport::topics::kFollowerObjectPosePrefix + scene.free_bodies()[b].name;
    const transport::TopicSpec<msg::ObjectPose> spec{topic.c_str(), transport::QosPreset::kStream};
    objects_.push_back(std::make_unique<ObjectFeed>());
    objects_.back()->body = b;
    objects_.back()->topic = topic;
    objects_.back()->reader = participant.make_reader(spec);
  }
}

BusLayers::~BusLayers() = default;

bool BusLayers::update(PosedScene& scene) {
  bool posed = false;
  for (auto& f : arms_) {
    bool fresh = false;
    if (f->is_command()) {
      while (f->command.take_next(f->command_sample)) {
        fresh = true;
        ++f->received;
      }
    } else {
      while (f->state.take_next(f->state_sample)) {
        fresh = true;
        ++f->received;
      }
    }
    if (!fresh) continue;
    bool ok = false;
    if (f->is_command()) {
      const auto& c = f->command_sample;
      ok = scene.set_joints(f->layer, f->arm, c.q_des_rad().data(), c.q_des_rad().size());
      f->last_ns = c.header().stamp_ns();
      f->last_seq = c.header().seq();
    } else {
      const auto& s = f->state_sample;
      const size_t n = s.q_rad().size();
      const bool full = s.dq_radps().size() == n && s.tau_measured_nm().size() == n;
      // only the follower's measured torques make its contact forces
      const bool torques = full && f->layer == Layer::kFollower;
      ok = scene.set_joints(f->layer, f->arm, s.q_rad().data(), n, full ? s.dq_radps().data() : nullptr,
                            torques ? s.tau_measured_nm().data() : nullptr);
      f->last_ns = s.header().stamp_ns();
      f->last_seq = s.header().seq();
    }
    if (!ok) ++f->mismatched;
    f->posed = f->posed || ok;
    posed = posed || ok;
  }
  for (auto& w : wrenches_) {
    while (w->reader.take_next(w->sample)) {
      ++w->received;
      w->last_ns = w->sample.header().stamp_ns();
      w->last_seq = w->sample.header().seq();
    }
  }
  for (auto& o : objects_) {
    bool fresh = false;
    while (o->reader.take_next(o->sample)) {
      fresh = true;
      ++o->received;
    }
    if (!fresh) continue;
    o->last_ns = o->sample.header().stamp_ns();
    o->last_seq = o->sample.header().seq();
    double position[3];
    double quaternion[4];
    transport::read_vector3(o->sample.world_pose().position_m(), position);
    transport::read_quaternion(o->sample.world_pose().orientation(), quaternion);
    scene.set_body_pose(Layer::kFollower, o->body, position, quaternion);
    posed = true;
  }
  return posed;
}

std::vector<ForceArrow> BusLayers::forces(PosedScene& scene) const {
  std::vector<ForceArrow> out;
  if (!scene.posed(Layer::kFollower)) return out;
  const mjData* d = scene.data(Layer::kFollower);
  for (const auto& w : wrenches_) {
    if (w->received == 0) continue;
    ForceArrow a;
    std::copy_n(d->site_xpos + 3 * scene.ee_site(w->arm), 3, a.from.begin());
    transport::read_vector3(w->sample.force_n(), a.force.data());
    out.push_back(a);
  }
  return out;
}

bool BusLayers::complete(Layer layer) const {
  // every arm posed by one of its layer's topics
  for (const auto& f : arms_) {
    if (f->layer != layer) continue;
    bool posed = false;
    for (const auto& g : arms_) posed = posed || (g->layer == layer && g->arm == f->arm && g->posed);
    if (!posed) return false;
  }
  return true;
}

std::string BusLayers::missing(Layer layer) const {
  std::string out;
  for (const auto& f : arms_) {
    if (f->layer != layer) continue;
    bool posed = false;
    std::string topics;
    for (const auto& g : arms_) {
      if (g->layer != layer || g->arm != f->arm) continue;
      posed = posed || g->posed;
      topics += (topics.empty() ? "" : " or ") + g->topic;
    }
    if (!posed && out.find(topics) == std::string::npos) out += (out.empty() ? "" : ", ") + topics;
  }
  return out;
}

std::string BusLayers::status(int64_t now_ns) const {
  std::string out;
  // the newest sample's number and age (the streams keep only the newest: what a frame takes is
  // not what was sent)
  auto line = [&](const std::string& topic, uint64_t received, int64_t last_ns, uint64_t last_seq,
                  uint64_t mismatched) {
    std::string state =
        received == 0 ? std::string("no data yet")
                      : fmt::format("seq {}, {:.0f} ms old", last_seq, static_cast<double>(now_ns - last_ns) * 1e-6);
    if (mismatched > 0) state += fmt::format(", {} with the wrong joint count", mismatched);
    out += (out.empty() ? "" : "\n") + topic + "\t" + state;
  };
  for (const auto& f : arms_) line(f->topic, f->received, f->last_ns, f->last_seq, f->mismatched);
  for (const auto& w : wrenches_) line(w->topic, w->received, w->last_ns, w->last_seq, 0);
  for (const auto& o : objects_) line(o->topic, o->received, o->last_ns, o->last_seq, 0);
  return out;
}

}  // namespace teleop::view
