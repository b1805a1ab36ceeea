#pragma once
// Options that take a configuration file by path or by name (`teleop launch demo`,
// `teleop topic list -c follower`): the name is resolved while the option is parsed
// (common/data_paths.h), so an unknown name fails like any bad option, saying where it looked.

#include <CLI/CLI.hpp>

#include <string>

#include "teleop/common/config.h"
#include "teleop/common/data_paths.h"

namespace teleop::cli {

/// Turns a name into config/<kind>/<name>.yaml (installed or in the source tree); leaves paths.
inline CLI::Validator named_config(const std::string& kind) {
  return CLI::Validator(
      [kind](std::string& value) -> std::string {
        try {
          value = resolve_config(kind, value);
        } catch (const ConfigError& e) {
          return e.what();
        }
        return {};
      },
      // the option's help says it takes a name; ExistingFile after it names the type
      "");
}

}  // namespace teleop::cli
