#pragma once
// A posed scene as the JSON messages of Foxglove's 3D panel: every body of each shown layer as a
// frame of the world ("follower/link3", foxglove.FrameTransforms), the geoms as primitives on their
// bodies' frames (foxglove.SceneUpdate: sent now and then, the frames move them), and forces as
// arrows in the world (foxglove.SceneUpdate). Quaternions: MuJoCo's (w, x, y, z) become Foxglove's
// {x, y, z, w}.

#include <cstdint>
#include <string>
#include <vector>

#include "teleop/view/posed_scene.h"
#include "teleop/view/scene_renderer.h"

namespace teleop::view {

/// The frame of `body` in `layer`: "<layer>/<body name>" ("<layer>/body<i>" for an unnamed one,
/// "world" for the world body).
std::string frame_id(const mjModel* m, Layer layer, int body);

/// The bodies of every posed layer of `shown` as frames with the world as parent.
std::string frame_transforms_json(PosedScene& scene, const std::vector<Layer>& shown, int64_t stamp_ns);

/// One entity per body of every posed layer of `shown`, its visible geoms as cubes, spheres and
/// cylinders on the body's frame (a capsule: a cylinder and two spheres; meshes and planes are
/// left out); the follower in the model's colours, the ghosts translucent.
std::string geometry_json(PosedScene& scene, const std::vector<Layer>& shown, int64_t stamp_ns);

/// The follower's contact forces (red) and the external forces at the flanges (orange) as arrows
/// of `metres_per_newton`, in the world frame; one entity, replaced by each message.
std::string forces_json(PosedScene& scene, const std::vector<ForceArrow>& flange_forces, double metres_per_newton,
                        int64_t stamp_ns);

}  // namespace teleop::view
