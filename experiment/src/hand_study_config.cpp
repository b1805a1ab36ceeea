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
  for (const ConfigNode& w : s.get_node_list("path")) {
    HandStudyWaypoint waypoint;
    waypoint.keyframe = w.get_string("keyframe");
    // the first waypoint is where the motion starts: it takes no time to reach
    waypoint.move_s = c.path.empty() ? 0.0 : w.get_double("move_s", Range{0.01, 600});
    c.path.push_back(waypoint);
  }
  if (c.path.empty()) throw s.error("path", "lists no keyframe (the first is the start, the last the pose held)");
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
    c.hand_torque_limit_nm = control->get_double("hand_torque_limit_nm", Range{0.001, 1e4}, c.hand_torque_limit_nm);
  }
  if (const auto contact = s.optional_child("contact")) {
    c.friction_cone = contact->get_choice("friction_cone", {"pyramidal", "elliptic"}, "");
    c.noslip_iterations = static_cast<int>(contact->get_int("noslip_iterations", Range{0, 1000}, -1));
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

double HandStudyConfig::motion_s() const {
  double total = 0.0;
  for (const HandStudyWaypoint& w : path) total += w.move_s;
  return total;
}

}  // namespace teleop::experiment
