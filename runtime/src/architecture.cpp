#include "teleop/runtime/architecture.h"

#include <array>

namespace teleop::runtime {
namespace {

// the built-in architectures (docs/architectures.md); a new one is a row here and its leader's
// strategy (leader/src/architectures/leader_architectures.cpp)
constexpr std::array<Architecture, 4> kArchitectures{{
    {"position_position", CommandPath::kLeaderJoint, false},
    {"pfc", CommandPath::kLeaderCartesian, false},
    {"pfc_tdpa", CommandPath::kLeaderCartesian, true},
    {"mmt", CommandPath::kTwin, false},
}};

double read_max_damping(const ConfigNode& tdpa, const std::string& key) {
  // 0 in the file means "no limit": YAML has no portable infinity
  const double v = tdpa.get_double(key, Range{0, 1e9}, 0.0);
  return v > 0 ? v : std::numeric_limits<double>::infinity();
}

}  // namespace

std::span<const Architecture> architectures() { return kArchitectures; }

const Architecture* find_architecture(std::string_view name) {
  for (const Architecture& a : kArchitectures) {
    if (a.name == name) return &a;
  }
  return nullptr;
}

std::optional<TeleoperationConfig> parse_teleoperation_config(const ConfigNode& root) {
  const auto section = root.optional_child("teleoperation");
  if (!section) return std::nullopt;
  std::vector<std::string> names;
  for (const Architecture& a : kArchitectures) names.emplace_back(a.name);
  TeleoperationConfig c;
  c.architecture = find_architecture(section->get_choice("architecture", names));
  if (const auto tdpa = section->optional_child("tdpa")) {
    c.tdpa.max_leader_damping = read_max_damping(*tdpa, "max_leader_damping");
    c.tdpa.max_follower_damping = read_max_damping(*tdpa, "max_follower_damping");
    c.tdpa.drift_time_constant_s = tdpa->get_double("drift_time_constant_s", Range{0, 60}, c.tdpa.drift_time_constant_s);
    c.tdpa.drift_max_speed_m_per_s =
        tdpa->get_double("drift_max_speed_m_per_s", Range{1e-6, 10}, c.tdpa.drift_max_speed_m_per_s);
    c.tdpa.drift_max_speed_rad_per_s =
        tdpa->get_double("drift_max_speed_rad_per_s", Range{1e-6, 10}, c.tdpa.drift_max_speed_rad_per_s);
    c.tdpa.drift_contact_force_n =
        tdpa->get_double("drift_contact_force_n", Range{1e-3, 1e4}, c.tdpa.drift_contact_force_n);
    c.tdpa.drift_contact_torque_nm =
        tdpa->get_double("drift_contact_torque_nm", Range{1e-3, 1e4}, c.tdpa.drift_contact_torque_nm);
  }
  return c;
}

}  // namespace teleop::runtime
