#include "leader_architectures.h"

#include <array>
#include <stdexcept>
#include <string>

#include "mmt.h"
#include "pfc.h"
#include "position_position.h"

namespace teleop::leader {
namespace {

using Factory = std::unique_ptr<LeaderArchitecture> (*)(const runtime::Architecture& a, const LeaderSetup& setup);

struct Entry {
  std::string_view name;
  Factory make;
};

template <typename Part>
std::unique_ptr<LeaderArchitecture> make(const runtime::Architecture& /*a*/, const LeaderSetup& setup) {
  return std::make_unique<Part>(setup);
}

// pfc and pfc_tdpa: one law, the TDPA controller on or off as the registry says
std::unique_ptr<LeaderArchitecture> make_pfc(const runtime::Architecture& a, const LeaderSetup& setup) {
  return std::make_unique<PfcLeader>(setup, a.tdpa_corrects);
}

// one row per architecture of runtime::architectures()
constexpr std::array<Entry, 4> kLeaderParts{{
    {"position_position", &make<PositionPositionLeader>},
    {"pfc", &make_pfc},
    {"pfc_tdpa", &make_pfc},
    {"mmt", &make<MmtLeader>},
}};

}  // namespace

std::unique_ptr<LeaderArchitecture> make_leader_architecture(const runtime::Architecture& architecture,
                                                             const LeaderSetup& setup) {
  for (const Entry& e : kLeaderParts) {
    if (e.name == architecture.name) return e.make(architecture, setup);
  }
  throw std::logic_error("the leader has no part for the architecture " + std::string(architecture.name) +
                         " (leader/src/architectures/leader_architectures.cpp)");
}

std::vector<std::string_view> leader_architecture_names() {
  std::vector<std::string_view> names;
  for (const Entry& e : kLeaderParts) names.push_back(e.name);
  return names;
}

}  // namespace teleop::leader
