#pragma once
// Parsing YAML that nobody can make hurt: before yaml-cpp builds its node tree, one pass over the
// parser's events checks what the strict configuration reader relies on. Linear in the text, so
// that a "billion laughs" (anchors nested in anchors, a few lines that mean 9^n nodes) is refused
// in microseconds instead of being walked for hours.

#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <string>

namespace teleop {

/// The most nodes aliases may add to a document: each alias counts the nodes of what it repeats
/// (expanded: its own aliases included), less one for itself. Anchors that name a block of gains
/// used in a few places add tens of nodes; an alias bomb adds 9^n.
inline constexpr uint64_t kMaxAliasedNodes = 100'000;
/// The deepest a value may sit below the document's top (aliases expanded): configuration files
/// are a few levels deep.
inline constexpr int kMaxYamlDepth = 64;

/// Parses the first YAML document of `text` after checking its events: every mapping key a plain
/// scalar given once, no value deeper than kMaxYamlDepth, no alias inside the node it names, and
/// at most kMaxAliasedNodes added by aliases. A broken rule throws ConfigError
/// "<source>:<line>: <path>: <problem>", where `path` is the dotted key path below `root_path`
/// (the key a `--set` value goes to; "" for a file). Malformed YAML throws YAML::ParserException:
/// the caller words it, knowing whether the text was a file or an argument.
YAML::Node parse_strict_yaml(const std::string& text, const std::string& source, const std::string& root_path = "");

}  // namespace teleop
