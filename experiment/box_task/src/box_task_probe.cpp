#include "teleop/box_task/box_task_probe.h"

#include <stdexcept>
#include <string>

namespace teleop::box_task {
namespace {

int id_or_throw(const mjModel* m, mjtObj type, const char* name) {
  const int id = mj_name2id(m, type, name);
  if (id < 0) throw std::invalid_argument(std::string("box task scene: no element named ") + name);
  return id;
}

bool in_subtree(const mjModel* m, int body, int root) {
  for (; body > 0; body = m->body_parentid[body]) {
    if (body == root) return true;
  }
  return false;
}

Eigen::Vector3d vec3(const mjtNum* p) { return {p[0], p[1], p[2]}; }

}  // namespace

BoxTaskProbe::BoxTaskProbe(const mjModel* scene)
    : kind_(static_cast<size_t>(scene->ngeom), Kind::kRobotBody),
      box_body_(id_or_throw(scene, mjOBJ_BODY, "box")),
      left_site_(id_or_throw(scene, mjOBJ_SITE, "left_ee_site")),
      right_site_(id_or_throw(scene, mjOBJ_SITE, "right_ee_site")) {
  const int left_arm = id_or_throw(scene, mjOBJ_BODY, "left_link0");
  const int right_arm = id_or_throw(scene, mjOBJ_BODY, "right_link0");
  for (int g = 0; g < scene->ngeom; ++g) {
    const int body = scene->geom_bodyid[g];
    Kind& kind = kind_[static_cast<size_t>(g)];
    if (body == box_body_) kind = Kind::kBox;
    else if (body == 0) kind = Kind::kEnvironment;  // static: table, socket, shelf, floor
    // (otherwise the robot's base, torso or head)
    else if (in_subtree(scene, body, left_arm)) kind = Kind::kLeftArm;
    else if (in_subtree(scene, body, right_arm)) kind = Kind::kRightArm;
  }
}

BoxTaskSample BoxTaskProbe::sample(const mjModel* m, const mjData* d) const {
  BoxTaskSample s;
  s.t_s = d->time;
  s.box_m = vec3(d->xpos + 3 * box_body_);
  s.left_m = vec3(d->site_xpos + 3 * left_site_);
  s.right_m = vec3(d->site_xpos + 3 * right_site_);
  for (int c = 0; c < d->ncon; ++c) {
    mjtNum force[6];
    mj_contactForce(m, d, c, force);  // contact frame: force[0] is the normal force
    const Kind a = kind_[static_cast<size_t>(d->contact[c].geom1)];
    const Kind b = kind_[static_cast<size_t>(d->contact[c].geom2)];
    auto pair = [&](Kind x, Kind y) { return (a == x && b == y) || (a == y && b == x); };
    if (pair(Kind::kLeftArm, Kind::kBox)) s.left_squeeze_n += force[0];
    if (pair(Kind::kRightArm, Kind::kBox)) s.right_squeeze_n += force[0];
    if (pair(Kind::kEnvironment, Kind::kBox)) s.support_n += force[0];
    // an arm touching anything but the box: furniture, the robot's own body, the other arm
    const bool arm_a = a == Kind::kLeftArm || a == Kind::kRightArm;
    const bool arm_b = b == Kind::kLeftArm || b == Kind::kRightArm;
    if ((arm_a && b != Kind::kBox) || (arm_b && a != Kind::kBox)) s.arm_collision_n += force[0];
  }
  return s;
}

BoxRegion shelf_region(const mjModel* scene, double tolerance_m) {
  auto lo = [&](const char* geom, int axis) {
    const int g = id_or_throw(scene, mjOBJ_GEOM, geom);
    return scene->geom_pos[3 * g + axis] - scene->geom_size[3 * g + axis];
  };
  auto hi = [&](const char* geom, int axis) {
    const int g = id_or_throw(scene, mjOBJ_GEOM, geom);
    return scene->geom_pos[3 * g + axis] + scene->geom_size[3 * g + axis];
  };
  const int box = id_or_throw(scene, mjOBJ_GEOM, "box");
  const Eigen::Vector3d half = vec3(scene->geom_size + 3 * box);
  BoxRegion region;
  region.min_m = {lo("shelf_floor", 0) + half.x(), lo("shelf_floor", 1), hi("shelf_floor", 2) + half.z() - tolerance_m};
  region.max_m = {lo("shelf_back", 0) - half.x(), hi("shelf_floor", 1), lo("shelf_ceiling", 2) - half.z()};
  return region;
}

}  // namespace teleop::box_task
