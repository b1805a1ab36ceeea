#include "teleop/launcher/scenario.h"

#include <filesystem>
#include <set>

#include "teleop/common/config.h"
#include "teleop/common/data_paths.h"

namespace teleop::launcher {
namespace fs = std::filesystem;
namespace {

// `config:` is a path, relative to the scenario's own folder (so a scenario copied elsewhere with
// its node configs beside it works), or a name of config/nodes (`follower`), as on every command
// line; a plain name that is also a file beside the scenario is that file
std::string node_config_path(const ConfigNode& n, const fs::path& base) {
  const fs::path config = n.get_string("config");
  const fs::path path = (config.is_absolute() ? config : base / config).lexically_normal();
  std::error_code ec;
  if (fs::exists(path, ec)) return path.string();
  if (!config.has_parent_path()) {
    try {
      return resolve_config("nodes", config.string());
    } catch (const ConfigError& e) {
      throw n.error("config", e.what());
    }
  }
  throw n.error("config", "file " + path.string() + " does not exist (a path is relative to the scenario's folder; a "
                          "name such as 'follower' is a shipped node config)");
}

}  // namespace

Scenario load_scenario(const std::string& path) {
  const ConfigNode root = ConfigNode::load_file(path);
  const ConfigNode s = root.child("scenario");
  Scenario scenario;
  scenario.file = path;
  scenario.name = s.get_string("name");
  scenario.duration_s = s.get_double("duration_s", Range{0, 1e6}, scenario.duration_s);
  scenario.stop_timeout_s = s.get_double("stop_timeout_s", Range{0.1, 600}, scenario.stop_timeout_s);
  const fs::path base = fs::path(path).parent_path();
  std::set<std::string> names;
  for (const ConfigNode& n : root.get_node_list("nodes")) {
    NodeLaunch node;
    node.name = n.get_string("name");
    if (!names.insert(node.name).second) throw n.error("name", "'" + node.name + "' is used by two nodes");
    node.executable = n.get_string("executable");
    node.config = node_config_path(n, base);
    node.args = n.get_string_list("args");
    node.site = n.get_string("site", "");
    if (const auto set = n.optional_child("set")) {
      for (const std::string& key : set->keys()) node.sets.push_back(key + "=" + set->get_yaml(key));
    }
    scenario.nodes.push_back(std::move(node));
  }
  if (scenario.nodes.empty()) throw root.error("nodes", "a scenario needs at least one node");
  root.check_all_used();
  return scenario;
}

}  // namespace teleop::launcher
