#include "foxglove_scene_json.h"

#include <gtest/gtest.h>

#include <array>
#include <nlohmann/json.hpp>

#include "teleop/view/view_model.h"

namespace teleop::view {
namespace {

using nlohmann::json;

const std::vector<Layer> kAllLayers{Layer::kFollower, Layer::kTwin, Layer::kLeader};

PosedScene follower_scene() {
  return PosedScene(read_view_model(std::string(TELEOP_SOURCE_DIR) + "/config/nodes/follower.yaml"));
}

void pose(PosedScene& scene, Layer layer) {
  const std::array<double, 7> q{0.3, -0.2, 0.1, -2.0, 0.0, 3.0, 0.7};
  ASSERT_TRUE(scene.set_joints(layer, 0, q.data(), q.size()));
  scene.update();
}

// Foxglove's {x, y, z, w} applied to a vector
std::array<double, 3> rotated(const json& q, std::array<double, 3> v) {
  const double mq[4] = {q["w"], q["x"], q["y"], q["z"]};
  double out[3];
  mju_rotVecQuat(out, v.data(), mq);
  return {out[0], out[1], out[2]};
}

TEST(FoxgloveSceneJson, NothingIsShownBeforeALayerIsPosed) {
  PosedScene scene = follower_scene();
  EXPECT_TRUE(json::parse(frame_transforms_json(scene, kAllLayers, 0))["transforms"].empty());
  EXPECT_TRUE(json::parse(geometry_json(scene, kAllLayers, 0))["entities"].empty());
}

TEST(FoxgloveSceneJson, EveryFollowerBodyIsAFrameOfTheWorldAtItsPose) {
  PosedScene scene = follower_scene();
  pose(scene, Layer::kFollower);
  const mjModel* m = scene.model();
  const mjData* d = scene.data(Layer::kFollower);
  const json transforms = json::parse(frame_transforms_json(scene, kAllLayers, 1'500'000'000))["transforms"];
  ASSERT_EQ(transforms.size(), static_cast<size_t>(m->nbody - 1));  // the world is the parent, not a frame
  for (int b = 1; b < m->nbody; ++b) {
    const json& t = transforms[static_cast<size_t>(b - 1)];
    EXPECT_EQ(t["parent_frame_id"], "world");
    EXPECT_EQ(t["child_frame_id"], frame_id(m, Layer::kFollower, b));
    EXPECT_DOUBLE_EQ(t["translation"]["z"].get<double>(), d->xpos[3 * b + 2]);
    EXPECT_DOUBLE_EQ(t["rotation"]["w"].get<double>(), d->xquat[4 * b]);
    EXPECT_EQ(t["timestamp"]["sec"], 1);
    EXPECT_EQ(t["timestamp"]["nsec"], 500'000'000);
  }
  EXPECT_EQ(frame_id(m, Layer::kTwin, 0), "world");
}

TEST(FoxgloveSceneJson, GeomsHangOnTheirBodiesFramesAndGhostsOnlyWhatTheArmsMove) {
  PosedScene scene = follower_scene();
  pose(scene, Layer::kFollower);
  pose(scene, Layer::kTwin);
  const mjModel* m = scene.model();
  const json entities = json::parse(geometry_json(scene, {Layer::kFollower, Layer::kTwin}, 0))["entities"];
  size_t follower = 0, twin = 0, primitives = 0;
  for (const json& e : entities) {
    EXPECT_EQ(e["id"], e["frame_id"]);
    EXPECT_TRUE(e["frame_locked"].get<bool>());
    const std::string frame = e["frame_id"];
    if (frame.rfind("twin/", 0) == 0) {
      ++twin;
      for (const json& c : e["cylinders"]) EXPECT_LT(c["color"]["a"].get<double>(), 1.0);  // a ghost
    } else {
      ++follower;
    }
    primitives += e["cubes"].size() + e["spheres"].size() + e["cylinders"].size();
  }
  EXPECT_EQ(follower, static_cast<size_t>(m->nbody));  // the world body's wall too
  EXPECT_GT(twin, 0u);
  EXPECT_LT(twin, follower);
  EXPECT_GT(primitives, 2 * twin);
}

TEST(FoxgloveSceneJson, ForceArrowsPointAlongTheForce) {
  PosedScene scene = follower_scene();
  const std::vector<ForceArrow> flange{{{0.5, 0.0, 0.6}, {0.0, 0.0, -20.0}}, {{0, 0, 0}, {-3.0, 0.0, 0.0}},
                                       {{0, 0, 0}, {0.0, 0.0, 0.0}}};
  const json entities = json::parse(forces_json(scene, flange, 0.01, 0))["entities"];
  ASSERT_EQ(entities.size(), 1u);
  EXPECT_EQ(entities[0]["frame_id"], "world");
  const json& arrows = entities[0]["arrows"];
  ASSERT_EQ(arrows.size(), 2u);  // no arrow for no force
  const auto down = rotated(arrows[0]["pose"]["orientation"], {1, 0, 0});
  EXPECT_NEAR(down[2], -1.0, 1e-9);
  EXPECT_NEAR(arrows[0]["shaft_length"].get<double>() + arrows[0]["head_length"].get<double>(), 0.2, 1e-9);
  EXPECT_EQ(arrows[0]["pose"]["position"]["x"], 0.5);
  const auto back = rotated(arrows[1]["pose"]["orientation"], {1, 0, 0});
  EXPECT_NEAR(back[0], -1.0, 1e-9);
}

}  // namespace
}  // namespace teleop::view
