#pragma once
// A node's parts of the architectures of the registry (runtime/architecture.h), as a static
// table of rows {name, factory} in the node's own folder (leader/src/architectures/
// leader_architectures.cpp, follower/src/architectures/follower_architectures.cpp): what finds a
// row by the architecture's name, and lists the table for the tests that check it against the
// registry. Setup time only.

#include <array>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "teleop/runtime/architecture.h"

namespace teleop::runtime {

template <typename Factory>
struct ArchitecturePart {
  std::string_view name;
  Factory make;
};

/// The factory of `architecture` in a node's table. Throws std::logic_error naming the node and
/// its table when the registry's architecture has no row there (a programming error).
template <typename Factory, std::size_t N>
Factory part_of(const std::array<ArchitecturePart<Factory>, N>& table, const Architecture& architecture,
                const char* node, const char* table_file) {
  for (const auto& row : table) {
    if (row.name == architecture.name) return row.make;
  }
  throw std::logic_error(std::string("the ") + node + " has no part for the architecture " +
                         std::string(architecture.name) + " (" + table_file + ")");
}

/// The table's names, in its order.
template <typename Factory, std::size_t N>
std::vector<std::string_view> part_names(const std::array<ArchitecturePart<Factory>, N>& table) {
  std::vector<std::string_view> names;
  for (const auto& row : table) names.push_back(row.name);
  return names;
}

}  // namespace teleop::runtime
