#include "teleop/experiment/experiment_config.h"

#include <set>

#include "teleop/common/config.h"
#include "teleop/launcher/launcher.h"
#include "teleop/launcher/scenario.h"
#include "teleop/sim/mujoco_model.h"
#include "teleop/box_task/box_task_probe.h"

namespace teleop::experiment {
namespace {

// the box task's arms and the shelf region its box must end in
void parse_box_task(const ConfigNode& a, AnalysisConfig& c) {
  c.arms = a.get_string_list("arms");
  if (c.arms.empty()) throw a.error("arms", "the box task needs the arms whose columns the traces prefix, e.g. [left, right]");
  const std::string scene = a.get_path("scene");
  try {
    c.shelf = box_task::shelf_region(sim::MujocoModel::load(scene).model());
  } catch (const std::exception& e) {
    throw a.error("scene", e.what());
  }
}

AnalysisConfig parse_analysis(const ConfigNode& a) {
  AnalysisConfig c;
  const bool box_task = a.get_choice("task", {"stiff_wall", "box_task"}, "stiff_wall") == "box_task";
  c.kind = box_task ? AnalysedTask::kBoxTask : AnalysedTask::kStiffWall;
  if (box_task) parse_box_task(a, c);
  c.leader = a.get_string("leader", c.leader);
  c.follower = a.get_string("follower", c.follower);
  if (c.leader == c.follower) throw a.error("follower", "must name another node than analysis.leader");
  c.settle_s = a.get_double("settle_s", Range{0, 1e6}, c.settle_s);
  const std::vector<double> hold = a.get_double_list("hold_window_s", Range{0, 1e6});
  if (a.has("hold_window_s")) {
    if (hold.size() != 2 || !(hold[0] < hold[1])) {
      throw a.error("hold_window_s", "expected [begin, end] with begin < end (seconds after the operator began)");
    }
    c.hold = {hold[0], hold[1]};
  }
  c.stable_max_mad_rad = a.get_double("stable_max_mad_rad", Range{0, 1e3}, c.stable_max_mad_rad);
  c.stable_max_saturation = a.get_double("stable_max_saturation", Range{0, 1}, c.stable_max_saturation);
  c.stable_max_force_mad_n = a.get_double("stable_max_force_mad_n", Range{0, 1e4}, c.stable_max_force_mad_n);
  c.stable_max_safe_hold = a.get_double("stable_max_safe_hold", Range{0, 1}, c.stable_max_safe_hold);
  if (a.has("max_flows_matched_s")) c.max_flows_matched_s = a.get_double("max_flows_matched_s", Range{0, 1e6});
  return c;
}

std::vector<RunSpec> parse_runs(const ConfigNode& e) {
  std::vector<RunSpec> runs;
  std::set<std::string> names;
  for (const ConfigNode& r : e.get_node_list("runs")) {
    RunSpec run{r.get_string("name"), r.get_path("scenario"), r.get_string_list("set")};
    if (run.name.empty() || run.name.find_first_of("/ ,") != std::string::npos) {
      throw r.error("name", "must be non-empty without '/', ',' or spaces (it names a folder and a table row)");
    }
    if (!names.insert(run.name).second) throw r.error("name", "'" + run.name + "' is used by two runs");
    // a broken scenario fails here, before the first run starts
    launcher::Scenario scenario;
    try {
      scenario = launcher::load_scenario(run.scenario);
    } catch (const ConfigError& error) {
      throw r.error("scenario", std::string("invalid scenario: ") + error.what());
    }
    // and so does an override naming no node of it
    try {
      for (const auto& node : scenario.nodes) launcher::node_overrides(scenario, node, run.sets);
    } catch (const ConfigError& error) {
      throw r.error("set", error.what());
    }
    runs.push_back(std::move(run));
  }
  if (runs.empty()) throw e.error("runs", "an experiment needs at least one run");
  return runs;
}

}  // namespace

ExperimentConfig load_experiment(const std::string& path) {
  const ConfigNode root = ConfigNode::load_file(path);
  const ConfigNode e = root.child("experiment");
  ExperimentConfig c;
  c.file = path;
  c.name = e.get_string("name");
  if (c.name.empty() || c.name.find('/') != std::string::npos) throw e.error("name", "must be non-empty without '/'");
  c.duration_s = e.get_double("duration_s", Range{0.1, 1e5}, c.duration_s);
  c.seed = static_cast<uint64_t>(e.get_int("seed", Range{0, 9.0e15}, static_cast<int64_t>(c.seed)));
  c.profiles = e.get_string_list("profiles");
  if (c.profiles.empty()) throw e.error("profiles", "needs at least one network profile ('none' = unimpaired)");
  c.runs = parse_runs(e);
  c.analysis =
      e.has("analysis") ? parse_analysis(e.child("analysis")) : parse_analysis(ConfigNode::load_string("{}", path));
  root.check_all_used();
  return c;
}

}  // namespace teleop::experiment
