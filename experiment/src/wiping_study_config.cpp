// The wiping study's file (config/experiments/wiping.yaml): read once, every error naming its key.
#include "parameter_sweep_config.h"
#include "sweep_parameters.h"
#include "teleop/common/config.h"
#include "teleop/experiment/wiping_study.h"

namespace teleop::experiment {
namespace {

WipingParameter read_parameter(const ConfigNode& section, const std::string& key) {
  const ConfigNode node = section.child(key);
  const SweepParameter p = read_sweep_parameter(node);
  if (!is_model_parameter(p.set)) throw node.error("set", "must change the model (the plan is the study's own)");
  return {p.name, p.set, p.values, node.get_double("planned", Range{-1e6, 1e6})};
}

WipingPlan read_plan(const ConfigNode& s) {
  WipingPlan p;
  p.tool_lean_rad = s.get_double("tool_lean_rad", Range{-1.2, 1.2}, p.tool_lean_rad);
  if (s.has("press_depth_m")) p.press_depth_m = s.get_double_list("press_depth_m", Range{-0.2, 0.2});
  if (p.press_depth_m.empty()) throw s.error("press_depth_m", "needs one depth per wipe");
  p.stroke_length_m = s.get_double("stroke_length_m", Range{0, 1}, p.stroke_length_m);
  p.stroke_spacing_m = s.get_double("stroke_spacing_m", Range{0, 0.5}, p.stroke_spacing_m);
  p.hover_m = s.get_double("hover_m", Range{0, 0.5}, p.hover_m);
  const Range time{0.01, 60};
  p.reach_s = s.get_double("reach_s", time, p.reach_s);
  p.press_s = s.get_double("press_s", time, p.press_s);
  p.stroke_s = s.get_double("stroke_s", time, p.stroke_s);
  p.lift_s = s.get_double("lift_s", time, p.lift_s);
  p.shift_s = s.get_double("shift_s", time, p.shift_s);
  p.settle_s = s.get_double("settle_s", time, p.settle_s);
  return p;
}

}  // namespace

bool is_wiping_study(const std::string& path) { return ConfigNode::load_file(path).has("wiping_study"); }

WipingStudyConfig load_wiping_study(const std::string& path) {
  const ConfigNode root = ConfigNode::load_file(path);
  const ConfigNode s = root.child("wiping_study");
  WipingStudyConfig c;
  c.file = path;
  c.name = s.get_string("name");
  c.model = twin::read_twin_model_config(s.child("model"));
  if (c.model.contact_pairs.empty()) throw s.child("model").error("contact_pairs", "needs the wiper-panel pair");
  c.hand_site = s.get_string("hand_site", c.hand_site);
  c.tool_site = s.get_string("tool_site", c.tool_site);
  c.panel_geom = s.get_string("panel_geom", c.panel_geom);
  c.wiper_angle = read_parameter(s, "wiper_angle");
  c.panel_height = read_parameter(s, "panel_height");
  c.plan = read_plan(s.child("plan"));
  const ConfigNode control = s.child("controller");
  c.translational_stiffness_n_per_m =
      control.get_double("translational_stiffness_n_per_m", Range{0, 1e5}, c.translational_stiffness_n_per_m);
  c.rotational_stiffness_nm_per_rad =
      control.get_double("rotational_stiffness_nm_per_rad", Range{0, 1e4}, c.rotational_stiffness_nm_per_rad);
  c.observer_gain_per_s = control.get_double("observer_gain_per_s", Range{1, 1000}, c.observer_gain_per_s);
  c.contact_force_n = s.get_double("contact_force_n", Range{0, 1e4}, c.contact_force_n);
  c.jobs = static_cast<int>(s.get_int("jobs", Range{1, 64}, c.jobs));
  root.check_all_used();
  return c;
}

}  // namespace teleop::experiment
