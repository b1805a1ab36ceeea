#pragma once
// The samples that pose a view, read from the bus: per arm the follower's measured joint state
// (teleop/follower/joint_state[/arm]), the twin's state (teleop/twin/joint_state[/arm]) and
// optionally the leader's command (teleop/leader/joint_command[/arm], its desired positions, or
// under MMT the device's teleop/leader/joint_state[/arm] that commands the twin); the
// follower's tracked objects (teleop/follower/object_pose/<body>) and its estimated external
// wrench (teleop/follower/wrench[/arm], drawn as an arrow at the flange). Readers only: the view writes
// nothing, so a node never waits for it, and its QoS is the nodes' own (best-effort streams: a
// slow view drops samples, never holds a writer back). Polled from the drawing thread.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "teleop/transport/participant.h"
#include "teleop/view/posed_scene.h"
#include "teleop/view/scene_renderer.h"

namespace teleop::view {

struct LayerChoice {
  bool twin = true;
  bool leader = false;
};

/// The layers of `chosen` that `scene` can show: the ghosts exist for arms on the arm topics; a
/// scene posed only by its own topics (the hand) has none.
LayerChoice shown_layers(const PosedScene& scene, LayerChoice chosen);

class BusLayers {
 public:
  /// Readers on `participant` for every arm of `scene` and each chosen layer (setup time).
  BusLayers(transport::Participant& participant, const PosedScene& scene, LayerChoice choice);
  ~BusLayers();
  BusLayers(const BusLayers&) = delete;
  BusLayers& operator=(const BusLayers&) = delete;

  /// Takes every sample that arrived; poses `scene` with the newest of each topic. Returns true
  /// when anything was posed.
  bool update(PosedScene& scene);

  /// The follower's newest external force of each arm that has one, at its flange in the
  /// follower's layer (the wrench's frame, the robot's base, taken as the world's).
  std::vector<ForceArrow> forces(PosedScene& scene) const;

  /// Whether every arm of `layer` has been posed (a layer not read counts as posed).
  bool complete(Layer layer) const;
  /// One line per topic (topic, a tab, its state): the newest sample's number and age, samples
  /// with the wrong joint count.
  std::string status(int64_t now_ns) const;
  /// The topics of `layer` whose arms have not been posed yet, comma-separated ("" when none).
  std::string missing(Layer layer) const;

 private:
  struct ArmFeed;
  struct ObjectFeed;
  struct WrenchFeed;
  std::vector<std::unique_ptr<ArmFeed>> arms_;
  std::vector<std::unique_ptr<ObjectFeed>> objects_;
  std::vector<std::unique_ptr<WrenchFeed>> wrenches_;
};

}  // namespace teleop::view
