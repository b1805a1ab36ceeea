#pragma once
// Options that take one of a few names for an enum (`teleop record --storage mcap|sqlite3`): a
// name not among them fails like any bad option, listing the names (CLI11's own transformers
// print their internal mapping instead).

#include <CLI/CLI.hpp>

#include <string>
#include <utility>
#include <vector>

namespace teleop::cli {

/// Turns each name into its enum value; any other text is an error naming the choices.
template <typename Enum>
CLI::Validator one_of(std::vector<std::pair<std::string, Enum>> choices) {
  return CLI::Validator(
      [choices = std::move(choices)](std::string& value) -> std::string {
        std::string names;
        for (const auto& [name, choice] : choices) {
          if (value == name) {
            value = std::to_string(static_cast<int>(choice));
            return {};
          }
          names += (names.empty() ? "" : ", ") + name;
        }
        return "'" + value + "' is not one of " + names;
      },
      "");
}

}  // namespace teleop::cli
