#include "teleop/view/foxglove_scene.h"

#include "foxglove_scene_json.h"
#include "teleop/common/clock.h"
#include "teleop/transport/participant.h"
#include "teleop/transport/participant_config.h"
#include "teleop/view/bus_layers.h"
#include "teleop/view/posed_scene.h"
#include "teleop/view/view_model.h"

namespace teleop::view {
namespace {

enum Channel : size_t { kTransforms = 0, kGeometry = 1, kForces = 2 };

// the geometry is sent again this often, for clients that subscribe later
constexpr int64_t kGeometryPeriodNs = 1'000'000'000;
// the force arrows' scale: 1 cm per N, as teleop view's
constexpr double kMetresPerNewton = 0.01;

// the top level of Foxglove's schemas, as far as the bridge fills them
std::string object_schema(const std::string& title, const std::vector<std::string>& arrays) {
  std::string properties;
  for (const std::string& a : arrays) {
    properties += (properties.empty() ? "" : ",") + ("\"" + a + "\":{\"type\":\"array\",\"items\":{\"type\":\"object\"}}");
  }
  return "{\"title\":\"" + title + "\",\"type\":\"object\",\"properties\":{" + properties + "}}";
}

std::vector<Layer> layers_of(LayerChoice shown) {
  std::vector<Layer> layers{Layer::kFollower};
  if (shown.twin) layers.push_back(Layer::kTwin);
  if (shown.leader) layers.push_back(Layer::kLeader);
  return layers;
}

}  // namespace

struct FoxgloveScene::Parts {
  PosedScene scene;
  std::vector<Layer> layers;
  transport::Participant participant;
  BusLayers bus;
  int64_t next_geometry_ns = 0;

  Parts(const std::string& scene_config, const std::string& bus_config, std::optional<int> domain)
      : scene(read_view_model(scene_config)),
        layers(layers_of(shown_layers(scene, {true, true}))),
        participant(transport::tool_participant_config(bus_config, domain, "teleop_bridge_scene")),
        bus(participant, scene, shown_layers(scene, {true, true})) {}
};

FoxgloveScene::FoxgloveScene(const std::string& scene_config, const std::string& bus_config,
                             std::optional<int> domain)
    : parts_(std::make_unique<Parts>(scene_config, bus_config, domain)) {}

FoxgloveScene::~FoxgloveScene() = default;

const std::vector<JsonChannel>& FoxgloveScene::channels() {
  static const std::vector<JsonChannel> list{
      {"scene/transforms", "foxglove.FrameTransforms", object_schema("foxglove.FrameTransforms", {"transforms"})},
      {"scene/geometry", "foxglove.SceneUpdate", object_schema("foxglove.SceneUpdate", {"deletions", "entities"})},
      {"scene/forces", "foxglove.SceneUpdate", object_schema("foxglove.SceneUpdate", {"deletions", "entities"})}};
  return list;
}

void FoxgloveScene::poll(std::vector<JsonMessage>& out) {
  Parts& p = *parts_;
  const bool posed = p.bus.update(p.scene);
  if (!p.scene.posed(Layer::kFollower) && !p.scene.posed(Layer::kTwin) && !p.scene.posed(Layer::kLeader)) return;
  const int64_t stamp_ns = system_now_ns();
  if (posed) {
    p.scene.update();
    out.push_back({kTransforms, frame_transforms_json(p.scene, p.layers, stamp_ns), stamp_ns});
    out.push_back({kForces, forces_json(p.scene, p.bus.forces(p.scene), kMetresPerNewton, stamp_ns), stamp_ns});
  }
  const int64_t now_ns = monotonic_now_ns();
  if (now_ns >= p.next_geometry_ns) {
    p.next_geometry_ns = now_ns + kGeometryPeriodNs;
    out.push_back({kGeometry, geometry_json(p.scene, p.layers, stamp_ns), stamp_ns});
  }
}

}  // namespace teleop::view
