#include "calibration_file.h"

#include <cstdio>
#include <filesystem>

#include "teleop/common/config.h"
#include "teleop/common/joint_config.h"

namespace teleop::follower {

control::ArmCalibration read_calibration(const std::string& path) {
  const ConfigNode root = ConfigNode::load_file(path);
  control::ArmCalibration c;
  const ConfigNode payload = root.child("payload");
  c.payload.mass_kg = payload.get_double("mass_kg", Range{0, 100});
  const std::array<double, 3> com = read_vector3(payload, "com_m", Range{-2, 2});
  c.payload.com_m = Eigen::Vector3d(com[0], com[1], com[2]);
  const JointVector bias = read_joint_list(root, "torque_bias_nm", control::kDof, Range{-50, 50}, 0.0);
  for (int i = 0; i < control::kDof; ++i) c.torque_bias_nm[i] = bias[static_cast<size_t>(i)];
  // how it was found: read so that a typo there is named too, kept for the reader
  if (const auto fit = root.optional_child("fit")) {
    fit->get_double("residual_rms_nm", Range{0, 1e3}, 0.0);
    fit->get_double("conditioning", Range{0, 1}, 0.0);
    fit->get_int("poses", Range{0, 10'000}, 0);
    fit->get_string("robot", "");
  }
  root.check_all_used();
  return c;
}

std::string calibration_file_of(const ConfigNode& section) {
  const std::string file = section.get_string("file", "");
  if (file.empty() || std::filesystem::path(file).is_absolute()) return file;
  return (std::filesystem::path(section.file()).parent_path() / file).lexically_normal().string();
}

PayloadCalibrationPlan read_calibration_plan(const ConfigNode& section) {
  PayloadCalibrationPlan plan;
  for (const ConfigNode& pose : section.get_node_list("poses")) {
    const JointVector q = read_joint_list(pose, "q_rad", control::kDof, kJointAngleRange, 0.0);
    if (!pose.has("q_rad")) throw pose.error("q_rad", "each pose needs its joint angles");
    plan.poses.push_back(Eigen::Map<const control::JointVector>(q.data()));
  }
  if (plan.poses.size() == 1) throw section.error("poses", "one pose cannot separate a payload from a bias: give 6 or more");
  plan.move_s = section.get_double("move_s", Range{0.1, 60}, plan.move_s);
  plan.approach_s = section.get_double("approach_s", Range{0.1, 60}, plan.approach_s);
  plan.settle_s = section.get_double("settle_s", Range{0, 60}, plan.settle_s);
  plan.measure_s = section.get_double("measure_s", Range{0.01, 60}, plan.measure_s);
  plan.approach_rad = section.get_double("approach_rad", Range{0, 0.5}, plan.approach_rad);
  plan.stiffness_nm_per_rad = section.get_double("stiffness_nm_per_rad", Range{1, 5000}, plan.stiffness_nm_per_rad);
  plan.damping_nms_per_rad = section.get_double("damping_nms_per_rad", Range{0, 500}, plan.damping_nms_per_rad);
  return plan;
}

control::ArmCalibration applied_calibration(const ConfigNode& section, const std::string& path) {
  if (!std::filesystem::exists(path)) {
    throw section.error("file", path + " does not exist: teleop_calibrate --config <this config> writes it (docs/calibration.md)");
  }
  return read_calibration(path);
}

std::string calibration_text(const control::PayloadFit& fit, const std::string& robot, size_t poses) {
  const control::ArmCalibration& c = fit.calibration;
  char text[1024];
  std::snprintf(text, sizeof(text),
                "# The calibration of a follower's robot (docs/calibration.md), written by teleop_calibrate;\n"
                "# applied at start by follower.calibration.file.\n"
                "payload:                 # on the flange, unknown to the robot's model\n"
                "  mass_kg: %.4f\n"
                "  com_m: [%.5f, %.5f, %.5f]   # centre of mass in the frame of the end-effector site\n"
                "torque_bias_nm: [%.4f, %.4f, %.4f, %.4f, %.4f, %.4f, %.4f]   # offset of the external-torque estimate\n"
                "fit:\n"
                "  residual_rms_nm: %.4f   # what the payload and the bias leave unexplained\n"
                "  conditioning: %.4f      # near 0: the poses could not tell the parameters apart\n"
                "  poses: %zu\n"
                "  robot: \"%s\"\n",
                c.payload.mass_kg, c.payload.com_m.x(), c.payload.com_m.y(), c.payload.com_m.z(), c.torque_bias_nm[0],
                c.torque_bias_nm[1], c.torque_bias_nm[2], c.torque_bias_nm[3], c.torque_bias_nm[4], c.torque_bias_nm[5],
                c.torque_bias_nm[6], fit.residual_rms_nm, fit.conditioning, poses, robot.c_str());
  return text;
}

}  // namespace teleop::follower
