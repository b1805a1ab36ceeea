#pragma once
// A follower's section from YAML text, for the tests of a backend's keys: the parse of
// `follower:` in a file named follower.yaml, or the ConfigError it throws.

#include <string>

#include "teleop/common/config.h"

namespace teleop::test {

/// What `parse` (a backend's section parser) makes of the `follower:` section of `yaml`.
template <typename Parse>
auto parse_follower_section(const std::string& yaml, Parse parse) {
  const ConfigNode root = ConfigNode::load_string(yaml, "follower.yaml");
  return parse(root.child("follower"))->config();
}

/// The ConfigError's message, or "" when the section parses.
template <typename Parse>
std::string follower_section_error(const std::string& yaml, Parse parse) {
  try {
    (void)parse_follower_section(yaml, parse);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

}  // namespace teleop::test
