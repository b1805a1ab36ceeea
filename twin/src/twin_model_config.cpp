#include "teleop/twin/twin_model_config.h"

#include <cmath>

#include "teleop/common/joint_config.h"
#include "teleop/sim/model_config.h"

namespace teleop::twin {

std::string read_side(const ConfigNode& node, const std::string& key) {
  std::string side = node.get_string(key);
  if (side.rfind("geom:", 0) != 0 && side.rfind("body:", 0) != 0) {
    throw node.error(key, "expected 'geom:NAME' or 'body:NAME', got '" + side + "'");
  }
  return side;
}

namespace {

std::vector<GeomPair> read_pairs(const ConfigNode& section, const std::string& key) {
  std::vector<GeomPair> pairs;
  for (const ConfigNode& p : section.get_node_list(key)) {
    pairs.push_back({p.get_string("name"), read_side(p, "a"), read_side(p, "b")});
  }
  return pairs;
}

void read_margins(const ConfigNode& section, TwinModelConfig& c) {
  const auto margins = section.optional_child("safety_margins");
  if (!margins) return;
  for (const ConfigNode& s : margins->get_node_list("spheres")) {
    c.margin_spheres.push_back({s.get_string("name"), s.get_string("body"), read_vector3(s, "pos_m", Range{-10, 10}),
                                s.get_double("radius_m", Range{1e-3, 2})});
  }
  for (const ConfigNode& p : margins->get_node_list("planes")) {
    c.margin_planes.push_back(
        {p.get_string("name"), read_vector3(p, "point_m", Range{-100, 100}), read_direction(p, "normal")});
  }
  c.margin_activation_m = margins->get_double("activation_m", Range{0, 0.5}, c.margin_activation_m);
}

std::vector<GeomOffset> read_geom_offsets(const ConfigNode& section) {
  std::vector<GeomOffset> offsets;
  for (const ConfigNode& o : section.get_node_list("geom_offsets")) {
    offsets.push_back({o.get_string("geom"), read_vector3(o, "offset_m", Range{-1, 1})});
  }
  return offsets;
}

}  // namespace

std::array<double, 3> read_direction(const ConfigNode& section, const std::string& key) {
  std::array<double, 3> v = read_vector3(section, key, Range{-1, 1});
  const double length = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  if (length < 1e-6) throw section.error(key, "must not be zero");
  for (double& x : v) x /= length;
  return v;
}

TwinModelConfig read_twin_model_config(const ConfigNode& section) {
  TwinModelConfig c;
  c.model_path = sim::get_model_path(section, "file");
  c.keyframe = section.get_string("keyframe", "");
  c.coupling_stiffness_nm_per_rad = section.get_double("coupling_stiffness_nm_per_rad", Range{0, 1e5}, c.coupling_stiffness_nm_per_rad);
  c.coupling_damping_nms_per_rad = section.get_double("coupling_damping_nms_per_rad", Range{0, 1e4}, c.coupling_damping_nms_per_rad);
  c.render_joint_friction = section.get_bool("render_joint_friction", c.render_joint_friction);
  read_margins(section, c);
  c.contact_pairs = read_pairs(section, "contact_pairs");
  c.distance_pairs = read_pairs(section, "distance_pairs");
  c.geom_offsets = read_geom_offsets(section);
  c.distance_range_m = section.get_double("distance_range_m", Range{1e-3, 100}, c.distance_range_m);
  return c;
}

}  // namespace teleop::twin
