#pragma once
// What the leader and follower share in reading a multi-arm configuration and building its
// logic: one config per entry of `<section>.arms` (arm name -> that arm's own keys on top of the
// shared section), and a run_node parser that builds one logic or an ArmGroup from them.

#include <string>
#include <utility>
#include <vector>

#include "teleop/common/config.h"
#include "teleop/runtime/node_runner.h"

namespace teleop::runtime {

/// One config per entry of `section.arms`, in the file's order: `apply(shared, name, arm_node)`
/// returns that arm's config; {shared} without `arms`. Throws ConfigError for an empty `arms`.
template <typename Config, typename Apply>
std::vector<Config> read_arm_configs(const ConfigNode& section, const Config& shared, Apply apply) {
  const auto arms = section.optional_child("arms");
  if (!arms) return {shared};
  std::vector<Config> configs;
  for (const std::string& name : arms->keys()) configs.push_back(apply(shared, name, arms->child(name)));
  if (configs.empty()) throw section.error("arms", "names no arm");
  return configs;
}

/// A parser for run_node: `parse(root)` gives the arms' configs before any DDS entity exists,
/// `build(configs, context)` the logic once the participant does.
template <typename Parse, typename Build>
LogicParser arm_logic_parser(Parse parse, Build build) {
  return [parse, build](const ConfigNode& root) -> LogicBuilder {
    auto configs = parse(root);
    return [configs = std::move(configs), build](NodeContext& context) { return build(configs, context); };
  };
}

}  // namespace teleop::runtime
