#include "teleop/common/joint_config.h"

#include <algorithm>

namespace teleop {

JointVector read_joint_list(const ConfigNode& section, const std::string& key, size_t joints, Range range,
                            double fallback) {
  JointVector out{};
  std::fill_n(out.begin(), joints, fallback);
  const auto values = section.get_double_list(key, range);
  if (values.empty()) return out;
  if (values.size() != joints) {
    throw section.error(key, "has " + std::to_string(values.size()) + " values, expected " + std::to_string(joints));
  }
  std::copy(values.begin(), values.end(), out.begin());
  return out;
}

std::array<double, 3> read_vector3(const ConfigNode& section, const std::string& key, Range range) {
  const std::vector<double> v = section.get_double_list(key, range);
  if (v.size() != 3) throw section.error(key, "expected 3 numbers (x, y, z), got " + std::to_string(v.size()));
  return {v[0], v[1], v[2]};
}

std::array<double, 3> read_vector3(const ConfigNode& section, const std::string& key, Range range,
                                   const std::array<double, 3>& fallback) {
  return section.has(key) ? read_vector3(section, key, range) : fallback;
}

size_t read_joint_count(const ConfigNode& section) {
  return static_cast<size_t>(section.get_int("joints", Range{1, static_cast<double>(kMaxJoints)}));
}

JointModelParams read_joint_model(const ConfigNode& section, size_t joints) {
  JointModelParams p;
  p.joints = joints;
  p.inertia_kgm2 = section.get_double("inertia_kgm2", Range{1e-4, 100}, p.inertia_kgm2);
  p.viscous_nms_per_rad = section.get_double("viscous_nms_per_rad", Range{0, 1000}, p.viscous_nms_per_rad);
  p.wall_joint = static_cast<size_t>(section.get_int("wall_joint", Range{0, static_cast<double>(joints) - 1}, 0));
  p.wall_q_rad = section.get_double("wall_q_rad", Range{-10, 1e9}, p.wall_q_rad);
  p.wall_stiffness_nm_per_rad = section.get_double("wall_stiffness_nm_per_rad", Range{0, 1e6}, p.wall_stiffness_nm_per_rad);
  return p;
}

}  // namespace teleop
