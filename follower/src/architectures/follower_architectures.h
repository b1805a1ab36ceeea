#pragma once
// The follower's part of every architecture of the registry (runtime/architecture.h), by name: a
// static table of the built-ins (follower_architectures.cpp), one row per architecture, no
// registration at start-up. docs/architecture.md, "A new teleoperation architecture".

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "follower_architecture.h"
#include "teleop/runtime/architecture.h"
#include "teleop/transport/participant.h"

namespace teleop::follower {

/// What an architecture's follower part is built from.
struct FollowerSetup {
  transport::Participant& participant;
  const std::string& node_name;
  const std::string& arm;
  double cycle_s;
  /// The `teleoperation:` section (its TDPA settings); null without one.
  const runtime::TeleoperationConfig* teleoperation;
};

/// Builds the follower's part of `setup.teleoperation`'s architecture (without the section: a
/// follower of joint commands). Setup time; throws std::logic_error for an architecture of the
/// registry without a follower's part (a row missing in the table).
std::unique_ptr<FollowerArchitecture> make_follower_architecture(const FollowerSetup& setup);

/// The architectures the follower has a part for, in the table's order (tests, docs).
std::vector<std::string_view> follower_architecture_names();

}  // namespace teleop::follower
