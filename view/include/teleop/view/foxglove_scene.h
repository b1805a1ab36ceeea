#pragma once
// The scene of a node config for Foxglove's 3D panel (`teleop bridge --scene`): the follower, the
// twin and the leader's command posed from the bus as `teleop view` poses them (BusLayers), turned
// into JSON messages of Foxglove's schemas: the bodies' frames (foxglove.FrameTransforms), the
// geoms on them (foxglove.SceneUpdate) and the forces as arrows (foxglove.SceneUpdate). Polled from
// one thread; it only reads the bus.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "teleop/common/json_channel.h"

namespace teleop::view {

class FoxgloveScene {
 public:
  /// The scene of the follower, twin or hand config `scene_config`; joins the bus as
  /// `bus_config` (a node config, or "" for the defaults) and `domain` say. Throws ConfigError,
  /// std::runtime_error for a model that does not load.
  FoxgloveScene(const std::string& scene_config, const std::string& bus_config, std::optional<int> domain);
  ~FoxgloveScene();
  FoxgloveScene(const FoxgloveScene&) = delete;
  FoxgloveScene& operator=(const FoxgloveScene&) = delete;

  /// scene/transforms, scene/geometry, scene/forces.
  static const std::vector<JsonChannel>& channels();

  /// Takes the newest samples and appends the messages due: the frames and forces whenever a
  /// sample posed the scene, the geometry once a second (a client that subscribes later gets it).
  /// Each message's channel is its index in channels().
  void poll(std::vector<JsonMessage>& out);

 private:
  struct Parts;
  std::unique_ptr<Parts> parts_;
};

}  // namespace teleop::view
