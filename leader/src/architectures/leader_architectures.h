#pragma once
// The leader's part of every architecture of the registry (runtime/architecture.h), by name: a
// static table of the built-ins (leader_architectures.cpp), one row per architecture, no
// registration at start-up. docs/architecture.md, "A new teleoperation architecture".

#include <memory>
#include <string_view>
#include <vector>

#include "leader_architecture.h"
#include "teleop/runtime/architecture.h"

namespace teleop::leader {

/// Builds the leader's part of `architecture`. Setup time; throws std::logic_error for an
/// architecture of the registry without a leader's part (a row missing in the table).
std::unique_ptr<LeaderArchitecture> make_leader_architecture(const runtime::Architecture& architecture,
                                                             const LeaderSetup& setup);

/// The architectures the leader has a part for, in the table's order (tests, docs).
std::vector<std::string_view> leader_architecture_names();

}  // namespace teleop::leader
