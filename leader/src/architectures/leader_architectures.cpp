#include "leader_architectures.h"

#include <array>

#include "mmt.h"
#include "pfc.h"
#include "position_position.h"
#include "teleop/runtime/architecture_parts.h"

namespace teleop::leader {
namespace {

using Factory = std::unique_ptr<LeaderArchitecture> (*)(const runtime::Architecture& a, const LeaderSetup& setup);

template <typename Part>
std::unique_ptr<LeaderArchitecture> make(const runtime::Architecture& /*a*/, const LeaderSetup& setup) {
  return std::make_unique<Part>(setup);
}

// pfc and pfc_tdpa: one law, the TDPA controller on or off as the registry says
std::unique_ptr<LeaderArchitecture> make_pfc(const runtime::Architecture& a, const LeaderSetup& setup) {
  return std::make_unique<PfcLeader>(setup, a.tdpa_corrects);
}

// one row per architecture of runtime::architectures()
constexpr std::array<runtime::ArchitecturePart<Factory>, 4> kLeaderParts{{
    {"position_position", &make<PositionPositionLeader>},
    {"pfc", &make_pfc},
    {"pfc_tdpa", &make_pfc},
    {"mmt", &make<MmtLeader>},
}};

}  // namespace

std::unique_ptr<LeaderArchitecture> make_leader_architecture(const runtime::Architecture& architecture,
                                                             const LeaderSetup& setup) {
  return runtime::part_of(kLeaderParts, architecture, "leader", "leader/src/architectures/leader_architectures.cpp")(
      architecture, setup);
}

std::vector<std::string_view> leader_architecture_names() { return runtime::part_names(kLeaderParts); }

}  // namespace teleop::leader
