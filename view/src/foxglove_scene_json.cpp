#include "foxglove_scene_json.h"

#include <mujoco/mujoco.h>

#include <array>
#include <cmath>
#include <nlohmann/json.hpp>

namespace teleop::view {
namespace {

using nlohmann::json;
using Vec3 = std::array<double, 3>;
using Rgba = std::array<double, 4>;

// the ghosts in one colour each, as teleop view draws them translucent
const Rgba kTwinColour{0.3, 0.5, 1.0, 0.35};
const Rgba kLeaderColour{0.3, 1.0, 0.4, 0.35};
const Rgba kContactColour{1.0, 0.15, 0.1, 1.0};
const Rgba kFlangeColour{1.0, 0.6, 0.0, 1.0};
// a force arrow no longer than this [m], and none for forces below a newton's thousandth
constexpr double kMaxArrowM = 0.5;
constexpr double kMinForceN = 1e-3;

json stamp(int64_t ns) { return {{"sec", ns / 1'000'000'000}, {"nsec", ns % 1'000'000'000}}; }
json vec(const double* v) { return {{"x", v[0]}, {"y", v[1]}, {"z", v[2]}}; }
json quat(const double* q) { return {{"x", q[1]}, {"y", q[2]}, {"z", q[3]}, {"w", q[0]}}; }
json pose(const double* position, const double* quaternion) {
  return {{"position", vec(position)}, {"orientation", quat(quaternion)}};
}
json colour(const Rgba& c) { return {{"r", c[0]}, {"g", c[1]}, {"b", c[2]}, {"a", c[3]}}; }
json size(double x, double y, double z) { return {{"x", x}, {"y", y}, {"z", z}}; }

// a ghost is only what the arms move; the follower's layer is the whole scene (the world body's
// geoms, a wall or a table, included: they are drawn on the world frame)
bool shown_body(PosedScene& scene, Layer layer, int body) {
  return layer == Layer::kFollower || (body > 0 && scene.moved_by_arms(body));
}

json empty_entity(const std::string& id, const std::string& frame, int64_t stamp_ns) {
  return {{"timestamp", stamp(stamp_ns)}, {"frame_id", frame},    {"id", id},
          {"lifetime", stamp(0)},         {"frame_locked", true}, {"metadata", json::array()},
          {"arrows", json::array()},      {"cubes", json::array()}, {"spheres", json::array()},
          {"cylinders", json::array()},   {"lines", json::array()}, {"triangles", json::array()},
          {"texts", json::array()},       {"models", json::array()}};
}

Rgba geom_colour(const mjModel* m, int g, Layer layer) {
  if (layer == Layer::kTwin) return kTwinColour;
  if (layer == Layer::kLeader) return kLeaderColour;
  const float* rgba = m->geom_matid[g] >= 0 ? m->mat_rgba + 4 * m->geom_matid[g] : m->geom_rgba + 4 * g;
  return {rgba[0], rgba[1], rgba[2], rgba[3]};
}

// a capsule's end caps: its centre +-half length along its own z, in the body's frame
void add_capsule_caps(json& entity, const mjModel* m, int g, const json& c) {
  const double* centre = m->geom_pos + 3 * g;
  const double* q = m->geom_quat + 4 * g;
  const double r = m->geom_size[3 * g];
  for (const double sign : {-1.0, 1.0}) {
    const double along[3] = {0, 0, sign * m->geom_size[3 * g + 1]};
    double offset[3];
    mju_rotVecQuat(offset, along, q);
    const double at[3] = {centre[0] + offset[0], centre[1] + offset[1], centre[2] + offset[2]};
    entity["spheres"].push_back({{"pose", pose(at, q)}, {"size", size(2 * r, 2 * r, 2 * r)}, {"color", c}});
  }
}

void add_geom(json& entity, const mjModel* m, int g, Layer layer) {
  const double* s = m->geom_size + 3 * g;
  const json p = pose(m->geom_pos + 3 * g, m->geom_quat + 4 * g);
  const json c = colour(geom_colour(m, g, layer));
  switch (m->geom_type[g]) {
    case mjGEOM_SPHERE:
      entity["spheres"].push_back({{"pose", p}, {"size", size(2 * s[0], 2 * s[0], 2 * s[0])}, {"color", c}});
      break;
    case mjGEOM_ELLIPSOID:
      entity["spheres"].push_back({{"pose", p}, {"size", size(2 * s[0], 2 * s[1], 2 * s[2])}, {"color", c}});
      break;
    case mjGEOM_BOX:
      entity["cubes"].push_back({{"pose", p}, {"size", size(2 * s[0], 2 * s[1], 2 * s[2])}, {"color", c}});
      break;
    case mjGEOM_CAPSULE:
      add_capsule_caps(entity, m, g, c);
      [[fallthrough]];
    case mjGEOM_CYLINDER:
      entity["cylinders"].push_back({{"pose", p},
                                     {"size", size(2 * s[0], 2 * s[0], 2 * s[1])},
                                     {"bottom_scale", 1.0},
                                     {"top_scale", 1.0},
                                     {"color", c}});
      break;
    default:  // planes (endless) and meshes (their vertices are not sent)
      break;
  }
}

// Foxglove's arrow points along its pose's +x: the rotation taking x onto `unit`
std::array<double, 4> x_onto(const Vec3& unit) {
  const double w = 1.0 + unit[0];  // 1 + x . unit
  if (w < 1e-9) return {0, 0, 0, 1};  // opposite: half a turn about z
  const std::array<double, 4> q{w, 0.0, -unit[2], unit[1]};  // (w, x cross unit)
  const double n = std::sqrt(q[0] * q[0] + q[2] * q[2] + q[3] * q[3]);
  return {q[0] / n, 0.0, q[2] / n, q[3] / n};
}

void add_arrow(json& entity, const Vec3& from, const Vec3& force, double metres_per_newton, const Rgba& c) {
  const double n = std::sqrt(force[0] * force[0] + force[1] * force[1] + force[2] * force[2]);
  if (n < kMinForceN) return;
  const std::array<double, 4> q = x_onto({force[0] / n, force[1] / n, force[2] / n});
  const double length = std::min(n * metres_per_newton, kMaxArrowM);
  entity["arrows"].push_back({{"pose", pose(from.data(), q.data())},
                              {"shaft_length", 0.8 * length},
                              {"shaft_diameter", 0.008},
                              {"head_length", 0.2 * length},
                              {"head_diameter", 0.02},
                              {"color", colour(c)}});
}

// the contact's force on the world: MuJoCo gives it in the contact's frame (normal first)
Vec3 contact_force(const mjModel* m, const mjData* d, int i) {
  mjtNum local[6];
  mj_contactForce(m, d, i, local);
  const mjtNum* frame = d->contact[i].frame;
  Vec3 world{};
  for (int axis = 0; axis < 3; ++axis) {
    for (int k = 0; k < 3; ++k) world[static_cast<size_t>(k)] += local[axis] * frame[3 * axis + k];
  }
  return world;
}

}  // namespace

std::string frame_id(const mjModel* m, Layer layer, int body) {
  const char* name = mj_id2name(m, mjOBJ_BODY, body);
  if (body == 0) return "world";
  return std::string(layer_name(layer)) + "/" + (name != nullptr && *name != 0 ? name : "body" + std::to_string(body));
}

std::string frame_transforms_json(PosedScene& scene, const std::vector<Layer>& shown, int64_t stamp_ns) {
  const mjModel* m = scene.model();
  json transforms = json::array();
  for (const Layer layer : shown) {
    if (!scene.posed(layer)) continue;
    const mjData* d = scene.data(layer);
    for (int b = 1; b < m->nbody; ++b) {
      if (!shown_body(scene, layer, b)) continue;
      transforms.push_back({{"timestamp", stamp(stamp_ns)},
                            {"parent_frame_id", "world"},
                            {"child_frame_id", frame_id(m, layer, b)},
                            {"translation", vec(d->xpos + 3 * b)},
                            {"rotation", quat(d->xquat + 4 * b)}});
    }
  }
  return json{{"transforms", transforms}}.dump();
}

std::string geometry_json(PosedScene& scene, const std::vector<Layer>& shown, int64_t stamp_ns) {
  const mjModel* m = scene.model();
  json entities = json::array();
  for (const Layer layer : shown) {
    if (!scene.posed(layer)) continue;
    for (int b = 0; b < m->nbody; ++b) {
      if (!shown_body(scene, layer, b)) continue;
      const std::string frame = frame_id(m, layer, b);
      json entity = empty_entity(frame, frame, stamp_ns);
      for (int g = m->body_geomadr[b]; g >= 0 && g < m->body_geomadr[b] + m->body_geomnum[b]; ++g) {
        // what MuJoCo's viewer shows by default: groups 0..2, not invisible
        if (m->geom_group[g] <= 2 && geom_colour(m, g, Layer::kFollower)[3] > 0) add_geom(entity, m, g, layer);
      }
      entities.push_back(std::move(entity));
    }
  }
  return json{{"deletions", json::array()}, {"entities", entities}}.dump();
}

std::string forces_json(PosedScene& scene, const std::vector<ForceArrow>& flange_forces, double metres_per_newton,
                        int64_t stamp_ns) {
  json entity = empty_entity("forces", "world", stamp_ns);
  if (scene.posed(Layer::kFollower)) {
    const mjModel* m = scene.model();
    const mjData* d = scene.data(Layer::kFollower);
    for (int i = 0; i < d->ncon; ++i) {
      const Vec3 from{d->contact[i].pos[0], d->contact[i].pos[1], d->contact[i].pos[2]};
      add_arrow(entity, from, contact_force(m, d, i), metres_per_newton, kContactColour);
    }
  }
  for (const ForceArrow& f : flange_forces) add_arrow(entity, f.from, f.force, metres_per_newton, kFlangeColour);
  return json{{"deletions", json::array()}, {"entities", json::array({entity})}}.dump();
}

}  // namespace teleop::view
