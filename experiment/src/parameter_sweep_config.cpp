#include "parameter_sweep_config.h"

#include <regex>

namespace teleop::experiment {
namespace {

PressScenario read_press(const ConfigNode& s) {
  PressScenario p;
  p.site = s.get_string("site", p.site);
  p.depth_m = s.get_double("depth_m", Range{0, 2}, p.depth_m);
  p.approach_time_s = s.get_double("approach_time_s", Range{0.001, 60}, p.approach_time_s);
  p.stiffness_n_per_m = s.get_double("stiffness_n_per_m", Range{0, 1e5}, p.stiffness_n_per_m);
  return p;
}

}  // namespace

SweepParameter read_sweep_parameter(const ConfigNode& p) {
  SweepParameter param{p.get_string("name"), p.get_string("set"), p.get_double_list("values", Range{-1e6, 1e6})};
  static const std::regex kSet(
      "(geom_pos_[xyz]|body_pos_[xyz]|geom_friction|body_angle_x):[A-Za-z0-9_.-]+|press_depth_m");
  if (!std::regex_match(param.set, kSet)) {
    throw p.error("set",
                  "expected geom_pos_x|y|z:NAME, body_pos_x|y|z:NAME, geom_friction:NAME, body_angle_x:NAME or "
                  "press_depth_m, got '" +
                      param.set + "'");
  }
  if (param.values.empty()) throw p.error("values", "needs at least one value");
  return param;
}

SweepConfig parse_sweep_config(const ConfigNode& root) {
  const ConfigNode s = root.child("sweep");
  SweepConfig c;
  c.model = twin::read_twin_model_config(s.child("model"));
  c.press = read_press(s.child("press"));
  c.duration_s = s.get_double("duration_s", Range{0.001, 3600}, c.duration_s);
  for (const ConfigNode& p : s.get_node_list("parameters")) c.parameters.push_back(read_sweep_parameter(p));
  if (c.parameters.empty()) throw s.error("parameters", "needs at least one parameter");
  c.jobs = static_cast<int>(s.get_int("jobs", Range{1, 64}, c.jobs));
  return c;
}

std::vector<std::vector<double>> sweep_grid(const std::vector<SweepParameter>& parameters) {
  std::vector<std::vector<double>> grid{{}};
  for (const SweepParameter& p : parameters) {
    std::vector<std::vector<double>> next;
    for (const auto& point : grid) {
      for (double v : p.values) {
        next.push_back(point);
        next.back().push_back(v);
      }
    }
    grid = std::move(next);
  }
  return grid;
}

}  // namespace teleop::experiment
