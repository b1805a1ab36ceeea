#pragma once
// Model files named in a node's configuration.

#include <string>

#include "teleop/common/config.h"

namespace teleop::sim {

/// Reads `key` of `section` as the path of an MJCF file (relative to the configuration file) and
/// loads it once: a model that is missing, malformed or does not compile is a configuration error
/// naming the file, the key and MuJoCo's message, found while the configuration is read, before
/// the node joins the network. Setup time only.
std::string get_model_path(const ConfigNode& section, const std::string& key);

}  // namespace teleop::sim
