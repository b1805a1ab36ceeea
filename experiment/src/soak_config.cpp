#include "teleop/common/config.h"
#include "teleop/experiment/soak.h"
#include "teleop/launcher/scenario.h"

namespace teleop::experiment {
namespace {

// [min, max] seconds, min <= max
std::pair<double, double> read_interval(const ConfigNode& s, const std::string& key, std::pair<double, double> fallback) {
  const std::vector<double> v = s.get_double_list(key, Range{0.01, 3600});
  if (!s.has(key)) return fallback;
  if (v.size() != 2 || v[0] > v[1]) throw s.error(key, "expected [min, max] seconds with min <= max");
  return {v[0], v[1]};
}

}  // namespace

SoakConfig load_soak(const std::string& path) {
  const ConfigNode root = ConfigNode::load_file(path);
  const ConfigNode s = root.child("soak");
  SoakConfig c;
  c.file = path;
  c.name = s.get_string("name");
  c.scenario_path = s.get_path("scenario");
  c.network = s.get_string("network", "");
  c.seed = static_cast<uint64_t>(s.get_int("seed", Range{0, 1e15}, static_cast<int64_t>(c.seed)));
  c.kills_per_node = static_cast<int>(s.get_int("kills_per_node", Range{1, 10'000}, c.kills_per_node));
  std::tie(c.up_min_s, c.up_max_s) = read_interval(s, "up_s", {c.up_min_s, c.up_max_s});
  std::tie(c.down_min_s, c.down_max_s) = read_interval(s, "down_s", {c.down_min_s, c.down_max_s});
  c.settle_s = s.get_double("settle_s", Range{0, 600}, c.settle_s);
  c.end_s = s.get_double("end_s", Range{0, 600}, c.end_s);
  c.resume_timeout_s = s.get_double("resume_timeout_s", Range{0.1, 3600}, c.resume_timeout_s);
  c.robot = s.get_string("robot", c.robot);
  // the scenario must name every node the soak talks about
  const launcher::Scenario scenario = launcher::load_scenario(c.scenario_path);
  const auto known = [&](const std::string& name) {
    for (const auto& n : scenario.nodes) {
      if (n.name == name) return true;
    }
    return false;
  };
  if (!known(c.robot)) throw s.error("robot", "'" + c.robot + "' is no node of " + c.scenario_path);
  const ConfigNode watch = s.child("watch");
  for (const std::string& node : watch.keys()) {
    if (!known(node)) throw watch.error(node, "'" + node + "' is no node of " + c.scenario_path);
    for (const std::string& watcher : watch.get_string_list(node)) {
      if (!known(watcher) || watcher == node) throw watch.error(node, "'" + watcher + "' cannot watch " + node);
      c.watch[node].push_back(watcher);
    }
  }
  if (c.watch.empty()) throw s.error("watch", "names no node to kill");
  root.check_all_used();
  return c;
}

}  // namespace teleop::experiment
