#include <cmath>
#include <set>

#include "teleop/common/config.h"
#include "teleop/experiment/hand_study.h"

namespace teleop::experiment {

HandStudyConfig load_hand_study(const std::string& path) {
  const ConfigNode root = ConfigNode::load_file(path);
  const ConfigNode s = root.child("hand_study");
  HandStudyConfig c;
  c.file = path;
  c.name = s.get_string("name");
  c.model_path = s.get_path("model");
  c.start_keyframe = s.get_string("start_keyframe", c.start_keyframe);
  c.goal_keyframe = s.get_string("goal_keyframe", c.goal_keyframe);
  c.move_s = s.get_double("move_s", Range{0, 600}, c.move_s);
  c.settle_s = s.get_double("settle_s", Range{0, 600}, c.settle_s);
  c.record_s = s.get_double("record_s", Range{0.01, 3600}, c.record_s);
  c.sample_period_s = s.get_double("sample_period_s", Range{1e-4, 1.0}, c.sample_period_s);
  c.mad_window = static_cast<size_t>(s.get_int("mad_window", Range{2, 10'000}, static_cast<int64_t>(c.mad_window)));
  if (c.record_s < static_cast<double>(c.mad_window) * c.sample_period_s) {
    throw s.error("record_s", "shorter than one running-mean window (mad_window x sample_period_s)");
  }
  if (const auto control = s.optional_child("control")) {
    c.arm_bandwidth_radps = control->get_double("arm_bandwidth_radps", Range{0.1, 300}, c.arm_bandwidth_radps);
    c.hand_bandwidth_radps = control->get_double("hand_bandwidth_radps", Range{0.1, 300}, c.hand_bandwidth_radps);
    c.damping_ratio = control->get_double("damping_ratio", Range{0.1, 10}, c.damping_ratio);
    c.servo_bandwidth_radps = control->get_double("servo_bandwidth_radps", Range{0.1, 900}, c.servo_bandwidth_radps);
  }
  std::set<std::string> names;
  for (const ConfigNode& r : s.get_node_list("runs")) {
    HandStudyRun run;
    run.name = r.get_string("name");
    if (!names.insert(run.name).second) throw r.error("name", "'" + run.name + "' is a second run of that name");
    run.link_inertia_kgm2 = r.get_double("link_inertia_kgm2", Range{1e-9, 10}, 0.0);
    const std::string coupling = r.get_choice("couplings", {"constraint", "servo"}, "constraint");
    run.coupling = coupling == "servo" ? hand::CouplingMode::kServo : hand::CouplingMode::kConstraint;
    c.runs.push_back(run);
  }
  if (c.runs.empty()) throw s.error("runs", "lists no run");
  root.check_all_used();
  return c;
}

}  // namespace teleop::experiment
