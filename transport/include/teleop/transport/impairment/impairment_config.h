#pragma once
// Which outgoing links of a participant are impaired, and how.

#include <cstdint>
#include <string>
#include <vector>

#include "teleop/common/config.h"
#include "teleop/transport/impairment/link_profile.h"

namespace teleop::transport::impairment {

/// The peer name that stands for every destination without a link of its own.
inline constexpr const char* kAnyPeer = "*";

struct LinkConfig {
  /// Peer participant (node) name the messages go to, or kAnyPeer.
  std::string to;
  LinkProfile profile;
};

struct ImpairmentConfig {
  /// Seeds every link's decisions (each link derives its own from it and its name).
  uint64_t seed = 1;
  /// Leave participant/endpoint discovery unimpaired (liveliness and user data still are).
  bool exclude_discovery = false;
  std::vector<LinkConfig> links;

  bool enabled() const { return !links.empty(); }
};

/// Reads `impairment:` of a transport section. Profile files are found relative to the config
/// file, then by name in the config/network folder next to it (`wan-35ms` ->
/// ../network/wan-35ms.yaml), then by name among teleop's own profiles (common/data_paths.h).
/// Throws ConfigError naming file and key.
ImpairmentConfig parse_impairment_config(const ConfigNode& section);

/// Resolves a profile given by path or by name, relative to `base_file`'s folder, else by name in
/// teleop's config/network (installed or of the source tree). Empty when there is none.
std::string resolve_profile_path(const std::string& profile, const std::string& base_file);

}  // namespace teleop::transport::impairment
