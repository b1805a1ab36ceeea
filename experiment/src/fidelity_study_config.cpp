#include <algorithm>
#include <cmath>
#include <set>

#include "teleop/common/config.h"
#include "teleop/experiment/fidelity_study.h"
#include "teleop/sim/actuated_joints.h"
#include "teleop/sim/model_config.h"
#include "teleop/sim/mujoco_model.h"

namespace teleop::experiment {
namespace {

control::JointVector joint_vector(const ConfigNode& node, const std::string& key, Range range) {
  const std::vector<double> values = node.get_double_list(key, range);
  if (values.size() != static_cast<size_t>(control::kDof)) {
    throw node.error(key, "needs " + std::to_string(control::kDof) + " values (one per joint), has " +
                              std::to_string(values.size()));
  }
  control::JointVector out;
  for (int i = 0; i < control::kDof; ++i) out[i] = values[static_cast<size_t>(i)];
  return out;
}

// every pose of the path inside the model's joint ranges, the path's poses known
void check_path(const FidelityStudyConfig& c, const ConfigNode& node, const FidelitySequence& s) {
  if (s.path.size() < 2) throw node.error("path", "needs a start and at least one pose to move to");
  const sim::MujocoModel model = sim::MujocoModel::load(s.model_path);
  const mjModel* m = model.model();
  const sim::ActuatedJoints joints = sim::find_actuated_joints(m, s.model_path);
  if (joints.count != static_cast<size_t>(control::kDof)) {
    throw node.error("model", "has " + std::to_string(joints.count) + " actuated joints, the study drives " +
                                  std::to_string(control::kDof));
  }
  for (const std::string& name : s.path) {
    const auto known = [&](const FidelityPose& p) { return p.name == name; };
    const auto pose = std::find_if(c.poses.begin(), c.poses.end(), known);
    if (pose == c.poses.end()) throw node.error("path", "names no pose of `poses`: '" + name + "'");
    for (size_t i = 0; i < joints.count; ++i) {
      const int joint = m->actuator_trnid[2 * joints.actuator[i]];
      const double q = pose->q_rad[static_cast<int>(i)];
      if (m->jnt_limited[joint] != 0 && (q <= m->jnt_range[2 * joint] || q >= m->jnt_range[2 * joint + 1])) {
        throw node.error("path", "pose '" + name + "' puts joint " + std::to_string(i + 1) + " at " +
                                     std::to_string(q) + " rad, not inside the model's range [" +
                                     std::to_string(m->jnt_range[2 * joint]) + ", " +
                                     std::to_string(m->jnt_range[2 * joint + 1]) + "]");
      }
    }
  }
}

}  // namespace

FidelityStudyConfig load_fidelity_study(const std::string& path) {
  const ConfigNode root = ConfigNode::load_file(path);
  const ConfigNode s = root.child("fidelity_study");
  FidelityStudyConfig c;
  c.file = path;
  c.name = s.get_string("name");
  c.ee_site = s.get_string("ee_site", c.ee_site);
  for (const double seed : s.get_double_list("seeds", Range{0, 9007199254740992.0})) {
    if (seed != std::floor(seed)) throw s.error("seeds", "holds " + std::to_string(seed) + ", not a whole number");
    c.seeds.push_back(static_cast<uint64_t>(seed));
  }
  if (c.seeds.empty()) throw s.error("seeds", "lists no seed");
  std::set<std::string> names;
  for (const ConfigNode& p : s.get_node_list("poses")) {
    FidelityPose pose;
    pose.name = p.get_string("name");
    if (!names.insert(pose.name).second) throw p.error("name", "'" + pose.name + "' is a second pose of that name");
    pose.q_rad = joint_vector(p, "q_rad", Range{-7, 7});
    c.poses.push_back(pose);
  }
  c.move_s = s.get_double("move_s", Range{0.01, 600}, c.move_s);
  c.hold_s = s.get_double("hold_s", Range{0.01, 600}, c.hold_s);
  c.pose_window_s = s.get_double("pose_window_s", Range{0.001, 600}, c.pose_window_s);
  if (c.pose_window_s > c.hold_s) throw s.error("pose_window_s", "is longer than hold_s");
  c.movement_before_s = s.get_double("movement_before_s", Range{0, 600}, c.movement_before_s);
  c.movement_after_s = s.get_double("movement_after_s", Range{0, 600}, c.movement_after_s);
  if (c.movement_before_s > c.hold_s || c.movement_after_s > c.hold_s) {
    throw s.error("movement_after_s", "a movement's margins must fit in the holds beside it (hold_s)");
  }
  c.trace_period_s = s.get_double("trace_period_s", Range{1e-4, 10}, c.trace_period_s);
  const ConfigNode controllers = s.child("controllers");
  const ConfigNode pd = controllers.child("state_space");
  c.state_space.kp = joint_vector(pd, "kp", Range{0, 1e5});
  c.state_space.kd = joint_vector(pd, "kd", Range{0, 1e4});
  const ConfigNode impedance = controllers.child("joint_impedance");
  c.joint_impedance.stiffness = joint_vector(impedance, "stiffness", Range{0, 1e5});
  c.joint_impedance.damping = joint_vector(impedance, "damping", Range{0, 1e4});
  // the robots' seeds are the study's `seeds`
  const ConfigNode real = s.child("real_robot");
  c.perturbation = sim::read_perturbation(real.child("perturbation"));
  c.sensor_noise = sim::read_sensor_noise(real.child("sensor_noise"));
  names.clear();
  for (const ConfigNode& q : s.get_node_list("sequences")) {
    FidelitySequence sequence;
    sequence.name = q.get_string("name");
    if (!names.insert(sequence.name).second) {
      throw q.error("name", "'" + sequence.name + "' is a second sequence of that name");
    }
    sequence.model_path = sim::get_model_path(q, "model");
    sequence.path = q.get_string_list("path");
    sequence.contact = q.get_bool("contact", false);
    check_path(c, q, sequence);
    c.sequences.push_back(sequence);
  }
  if (c.sequences.empty()) throw s.error("sequences", "lists no sequence");
  root.check_all_used();
  return c;
}

}  // namespace teleop::experiment
