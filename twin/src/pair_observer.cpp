#include "teleop/twin/pair_observer.h"

#include <algorithm>
#include <stdexcept>
#include <utility>

namespace teleop::twin {
namespace {

// MuJoCo's narrow phase for two geoms; its table holds each combination once, lower type first
mjfCollision collision_function(const mjModel* m, int& g1, int& g2) {
  if (m->geom_type[g1] > m->geom_type[g2]) std::swap(g1, g2);
  return mjCOLLISIONFUNC[m->geom_type[g1]][m->geom_type[g2]];
}

}  // namespace

bool PairObserver::Side::contains(int g) const { return std::find(geoms.begin(), geoms.end(), g) != geoms.end(); }

PairObserver::Side PairObserver::resolve(const mjModel* m, const std::string& side, const std::string& pair,
                                         const std::string& model_name) {
  const bool is_body = side.rfind("body:", 0) == 0;
  const std::string name = side.substr(5);
  const int id = mj_name2id(m, is_body ? mjOBJ_BODY : mjOBJ_GEOM, name.c_str());
  if (id < 0) throw std::runtime_error("pair '" + pair + "': MuJoCo model '" + model_name + "' has no " + side);
  Side s;
  if (!is_body) {
    s.geoms.push_back(id);
    return s;
  }
  for (int g = 0; g < m->ngeom; ++g) {
    if (m->geom_bodyid[g] == id && (m->geom_contype[g] != 0 || m->geom_conaffinity[g] != 0)) s.geoms.push_back(g);
  }
  if (s.geoms.empty()) throw std::runtime_error("pair '" + pair + "': " + side + " has no colliding geometry");
  return s;
}

PairObserver::PairObserver(const mjModel* m, const std::vector<GeomPair>& pairs, const std::string& model_name) {
  for (const GeomPair& p : pairs) {
    Pair resolved{p.name, resolve(m, p.a, p.name, model_name), resolve(m, p.b, p.name, model_name)};
    for (int ga : resolved.a.geoms) {
      for (int gb : resolved.b.geoms) {
        int g1 = ga;
        int g2 = gb;
        if (collision_function(m, g1, g2) == nullptr) {
          throw std::runtime_error("pair '" + p.name + "': MuJoCo cannot compute the distance between geoms '" +
                                   mj_id2name(m, mjOBJ_GEOM, g1) + "' and '" + mj_id2name(m, mjOBJ_GEOM, g2) + "'");
        }
      }
    }
    pairs_.push_back(std::move(resolved));
  }
}

Wrench PairObserver::contact_wrench(const mjModel* m, const mjData* d, size_t i) const {
  const Pair& p = pairs_[i];
  Wrench w;
  for (int c = 0; c < d->ncon; ++c) {
    const mjContact& con = d->contact[c];
    // the contact force pushes geom2 along the normal (away from geom1)
    double sign = 0.0;
    if (p.a.contains(con.geom2) && p.b.contains(con.geom1)) sign = 1.0;
    if (p.a.contains(con.geom1) && p.b.contains(con.geom2)) sign = -1.0;
    if (sign == 0.0) continue;
    mjtNum local[6];
    mj_contactForce(m, d, c, local);
    mjtNum world[3];
    mju_mulMatTVec(world, con.frame, local, 3, 3);
    mjtNum moment[3];
    mju_cross(moment, con.pos, world);
    for (size_t k = 0; k < 3; ++k) {
      w.force_n[k] += sign * world[k];
      w.torque_nm[k] += sign * moment[k];
    }
  }
  return w;
}

int PairObserver::contact_count(const mjData* d, size_t i) const {
  const Pair& p = pairs_[i];
  int count = 0;
  for (int c = 0; c < d->ncon; ++c) {
    const int g1 = d->contact[c].geom1;
    const int g2 = d->contact[c].geom2;
    if ((p.a.contains(g1) && p.b.contains(g2)) || (p.a.contains(g2) && p.b.contains(g1))) ++count;
  }
  return count;
}

double PairObserver::distance(const mjModel* m, const mjData* d, size_t i, double range_m) const {
  const Pair& p = pairs_[i];
  double best = range_m;
  mjContact contacts[mjMAXCONPAIR];
  for (int ga : p.a.geoms) {
    for (int gb : p.b.geoms) {
      int g1 = ga;
      int g2 = gb;
      const mjfCollision collide = collision_function(m, g1, g2);
      // the narrow phase reports every contact closer than the margin, with its signed distance
      const int n = collide(m, d, contacts, g1, g2, range_m);
      for (int k = 0; k < n; ++k) best = std::min(best, static_cast<double>(contacts[k].dist));
    }
  }
  return best;
}

}  // namespace teleop::twin
