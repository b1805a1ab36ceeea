#pragma once
// Command lines of the shipped nodes and of `teleop` tools on a test's domain.

#include <string>
#include <vector>

#include "process_helpers.h"

namespace teleop::test {

/// teleop_<role> with the shipped config (copied into `dir`) for `seconds` on `domain`.
inline std::vector<std::string> node(const std::string& dir, const std::string& role, int domain, double seconds) {
  return {bin("teleop_" + role),
          "--config",
          config_copy(dir, role + ".yaml", {}),
          "--domain",
          std::to_string(domain),
          "--duration",
          std::to_string(seconds)};
}

/// teleop ARGS --domain DOMAIN
inline std::vector<std::string> tool(std::vector<std::string> args, int domain) {
  args.insert(args.begin(), bin("teleop"));
  args.insert(args.end(), {"--domain", std::to_string(domain)});
  return args;
}

}  // namespace teleop::test
