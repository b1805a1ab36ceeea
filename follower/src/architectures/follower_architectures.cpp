#include "follower_architectures.h"

#include <array>

#include "joint_command_follower.h"
#include "pfc_follower.h"
#include "teleop/runtime/architecture_parts.h"

namespace teleop::follower {
namespace {

using Factory = std::unique_ptr<FollowerArchitecture> (*)(const FollowerSetup& setup);

std::unique_ptr<FollowerArchitecture> make_joint(const FollowerSetup& /*setup*/) {
  return std::make_unique<JointCommandFollower>();
}

// pfc and pfc_tdpa: one end of the channel, its controller on or off as the registry says
std::unique_ptr<FollowerArchitecture> make_pfc(const FollowerSetup& s) {
  return std::make_unique<PfcFollower>(s.participant, s.node_name, s.arm, s.cycle_s,
                                       s.teleoperation->architecture->tdpa_corrects, s.teleoperation->tdpa);
}

// one row per architecture of runtime::architectures()
constexpr std::array<runtime::ArchitecturePart<Factory>, 4> kFollowerParts{{
    {"position_position", &make_joint},
    {"pfc", &make_pfc},
    {"pfc_tdpa", &make_pfc},
    {"mmt", &make_joint},  // the twin's joint commands (follower.command_source: twin)
}};

}  // namespace

std::unique_ptr<FollowerArchitecture> make_follower_architecture(const FollowerSetup& setup) {
  if (setup.teleoperation == nullptr) return std::make_unique<JointCommandFollower>();
  return runtime::part_of(kFollowerParts, *setup.teleoperation->architecture, "follower",
                          "follower/src/architectures/follower_architectures.cpp")(setup);
}

std::vector<std::string_view> follower_architecture_names() { return runtime::part_names(kFollowerParts); }

}  // namespace teleop::follower
