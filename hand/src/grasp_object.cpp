#include "teleop/hand/grasp_object.h"

#include <algorithm>
#include <stdexcept>

namespace teleop::hand {

GraspObject::GraspObject(HandPlant& hand, const std::string& body, const std::string& support)
    : hand_(hand), body_(hand.mujoco().body_id(body)), hand_root_(hand.mujoco().body_id("svh_mount")) {
  const mjModel* m = hand_.model();
  const int joint = m->body_jntadr[body_];
  if (joint < 0 || m->body_jntnum[body_] != 1 || m->jnt_type[joint] != mjJNT_FREE) {
    throw std::runtime_error("MuJoCo model '" + hand_.mujoco().path() + "': body '" + body +
                             "' is to be grasped and needs exactly one free joint");
  }
  support_ = mj_name2id(m, mjOBJ_EQUALITY, support.c_str());
  if (support_ < 0) {
    throw std::out_of_range("MuJoCo model '" + hand_.mujoco().path() + "' has no equality '" + support + "'");
  }
}

bool GraspObject::supported() const { return hand_.model()->eq_active[support_] != 0; }

void GraspObject::release() { hand_.model()->eq_active[support_] = 0; }

void GraspObject::restore() { hand_.model()->eq_active[support_] = 1; }

std::array<double, 3> GraspObject::position_m() const {
  const mjtNum* x = hand_.data()->xipos + 3 * body_;
  return {x[0], x[1], x[2]};
}

bool GraspObject::is_hand_geom(int geom) const {
  const mjModel* m = hand_.model();
  // walk up from the geom's body to the world: the hand's geoms have the hand's root above them
  for (int b = m->geom_bodyid[geom]; b > 0; b = m->body_parentid[b]) {
    if (b == hand_root_) return true;
  }
  return false;
}

int GraspObject::hand_body_touching(const mjContact& c) const {
  const mjModel* m = hand_.model();
  if (m->geom_bodyid[c.geom1] == body_ && is_hand_geom(c.geom2)) return m->geom_bodyid[c.geom2];
  if (m->geom_bodyid[c.geom2] == body_ && is_hand_geom(c.geom1)) return m->geom_bodyid[c.geom1];
  return -1;
}

int GraspObject::hand_contacts() const {
  const mjData* d = hand_.data();
  int count = 0;
  for (int i = 0; i < d->ncon; ++i) count += hand_body_touching(d->contact[i]) >= 0 ? 1 : 0;
  return count;
}

int GraspObject::touching_links() const {
  const mjData* d = hand_.data();
  // a grasp's contact list is short (tens): the distinct hand bodies in a fixed list, no allocation
  constexpr int kMaxLinks = 64;
  int seen[kMaxLinks];
  int links = 0;
  for (int i = 0; i < d->ncon && links < kMaxLinks; ++i) {
    const int link = hand_body_touching(d->contact[i]);
    if (link < 0 || std::find(seen, seen + links, link) != seen + links) continue;
    seen[links++] = link;
  }
  return links;
}

double GraspObject::hand_contact_force_n() const {
  const mjModel* m = hand_.model();
  const mjData* d = hand_.data();
  double sum = 0.0;
  for (int i = 0; i < d->ncon; ++i) {
    if (hand_body_touching(d->contact[i]) < 0) continue;
    mjtNum force[6];
    mj_contactForce(m, d, i, force);
    sum += force[0];  // the normal component, in the contact frame
  }
  return sum;
}

double GraspObject::mass_kg() const { return hand_.model()->body_mass[body_]; }

}  // namespace teleop::hand
