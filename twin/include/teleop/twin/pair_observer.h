#pragma once
// Observes configured geometry pairs of a simulation: the contact wrench between the two sides of
// a pair and their minimum distance. Real-time safe after construction.

#include <mujoco/mujoco.h>

#include <array>
#include <string>
#include <vector>

#include "teleop/twin/twin_model_config.h"

namespace teleop::twin {

/// Force [N] and torque about the world origin [N*m] acting on side `a`, world frame.
struct Wrench {
  std::array<double, 3> force_n{};
  std::array<double, 3> torque_nm{};
};

class PairObserver {
 public:
  /// Resolves the sides ("geom:NAME" / "body:NAME": that body's colliding geoms). Throws
  /// std::runtime_error naming the pair and side when an element does not exist or has no geometry.
  PairObserver(const mjModel* m, const std::vector<GeomPair>& pairs, const std::string& model_name);

  size_t size() const { return pairs_.size(); }
  const std::string& name(size_t i) const { return pairs_[i].name; }

  /// Sum of the contact forces side b exerts on side a in the current data (its contact list).
  Wrench contact_wrench(const mjModel* m, const mjData* d, size_t i) const;
  /// Contacts between the two sides in the current data.
  int contact_count(const mjData* d, size_t i) const;
  /// Smallest signed distance between any geom of side a and any of side b [m], negative when
  /// they penetrate; `range_m` when none is closer than that. Needs the positions of the current
  /// data (mj_kinematics or a step). Every combination was checked at construction.
  double distance(const mjModel* m, const mjData* d, size_t i, double range_m) const;

 private:
  struct Side {
    std::vector<int> geoms;
    bool contains(int g) const;
  };
  struct Pair {
    std::string name;
    Side a;
    Side b;
  };
  static Side resolve(const mjModel* m, const std::string& side, const std::string& pair, const std::string& model_name);

  std::vector<Pair> pairs_;
};

}  // namespace teleop::twin
