#pragma once
// What the twin's simulation is made of: the MuJoCo model, the coupling (PARTI eq. 2), the
// rendering (eq. 3), the safety-margin geometry only the twin sees (§3.1) and the geometry pairs
// whose contact wrenches and distances are observed.

#include <array>
#include <string>
#include <vector>

#include "teleop/common/config.h"

namespace teleop::twin {

/// A sphere around a point of a body (e.g. an end effector), in the body's frame.
struct MarginSphere {
  std::string name;
  std::string body;
  std::array<double, 3> pos_m{};
  double radius_m = 0.1;
};

/// A virtual wall: the half-space behind the plane through `point_m` with outward `normal`.
struct MarginPlane {
  std::string name;
  std::array<double, 3> point_m{};
  std::array<double, 3> normal{0, 0, 1};
};

/// Two sides, each a geom or a body (all its geoms): "geom:NAME" or "body:NAME".
struct GeomPair {
  std::string name;
  std::string a;
  std::string b;
};

/// A deliberate model error (experiments, tests: "the twin's wall is 2 cm off"): the geom moved by
/// `offset_m` in its body's frame (the world's for a geom of the world body) when the model loads.
struct GeomOffset {
  std::string geom;
  std::array<double, 3> offset_m{};
};

struct TwinModelConfig {
  std::string model_path;
  /// Start pose ("" = the model's default state).
  std::string keyframe;
  /// The driven joints: the actuated hinge joints whose names start with each prefix, one arm
  /// after the other in this order (twin.arms). Empty: every actuated hinge joint.
  std::vector<std::string> joint_prefixes;
  /// Control period; the model's timestep must divide it. 0: one timestep (lock-step).
  double period_s = 0.001;
  /// K and D of PARTI eq. 2, per coupled joint.
  double coupling_stiffness_nm_per_rad = 300.0;
  double coupling_damping_nms_per_rad = 10.0;
  /// Render joint friction (MuJoCo frictionloss rows) too; off: contacts and limits only.
  bool render_joint_friction = false;
  std::vector<MarginSphere> margin_spheres;
  std::vector<MarginPlane> margin_planes;
  /// The margins' contact starts this far before their surfaces touch (MuJoCo's geom `margin`):
  /// the soft contact's spring then balances with the surfaces this much apart instead of inside
  /// each other. 0: at touch. Sizing it: docs/twin.md "Safety margins".
  double margin_activation_m = 0.0;
  std::vector<GeomPair> contact_pairs;
  std::vector<GeomPair> distance_pairs;
  std::vector<GeomOffset> geom_offsets;
  /// Distances beyond this are reported as this value [m] (the collision test's search margin).
  double distance_range_m = 1.0;
};

/// A pair side, "geom:NAME" or "body:NAME" (not resolved here). Throws ConfigError.
std::string read_side(const ConfigNode& node, const std::string& key);

/// A direction (three numbers in [-1, 1], not all zero) scaled to unit length. Throws ConfigError.
std::array<double, 3> read_direction(const ConfigNode& section, const std::string& key);

/// Reads the `model:` part of the twin section (paths relative to the config file).
TwinModelConfig read_twin_model_config(const ConfigNode& section);

}  // namespace teleop::twin
