// A robot's calibration file and the follower's `calibration:` section (follower/calibration_file.h):
// what teleop_calibrate writes reads back, a malformed file is named with its key, a node refuses
// to start without the file it names, the calibration tool parses without it.
#include <gtest/gtest.h>

#include <filesystem>

#include "calibration_file.h"
#include "process_helpers.h"
#include "teleop/common/config.h"
#include "teleop/follower/follower_config.h"

namespace teleop::follower {
namespace {

control::PayloadFit a_fit() {
  control::PayloadFit fit;
  fit.calibration.payload.mass_kg = 1.1837;
  fit.calibration.payload.com_m = Eigen::Vector3d(0.02043, -0.00999, 0.0624);
  fit.calibration.torque_bias_nm << 0.0, 0.0474, 0.0008, -0.0729, -0.0026, -0.008, -0.0004;
  fit.residual_rms_nm = 0.0061;
  fit.conditioning = 0.0477;
  return fit;
}

std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(CalibrationFile, WhatTheToolWritesReadsBack) {
  const std::string path = test::make_temp_dir() + "/panda.yaml";
  test::write_file(path, calibration_text(a_fit(), "mujoco:scene_wall.xml", 8));
  const control::ArmCalibration read = read_calibration(path);
  EXPECT_NEAR(read.payload.mass_kg, 1.1837, 1e-9);
  EXPECT_TRUE(read.payload.com_m.isApprox(a_fit().calibration.payload.com_m, 1e-9)) << read.payload.com_m.transpose();
  EXPECT_TRUE(read.torque_bias_nm.isApprox(a_fit().calibration.torque_bias_nm, 1e-9)) << read.torque_bias_nm.transpose();
}

TEST(CalibrationFile, AMalformedFileIsNamedWithItsKey) {
  const std::string path = test::make_temp_dir() + "/bad.yaml";
  test::write_file(path, "payload: {mass_kg: -1, com_m: [0, 0, 0]}\n");
  const std::string negative = message_of([&] { read_calibration(path); });
  EXPECT_NE(negative.find("bad.yaml"), std::string::npos) << negative;
  EXPECT_NE(negative.find("mass_kg"), std::string::npos) << negative;
  test::write_file(path, "payload: {mass_kg: 1, com_m: [0, 0, 0]}\nbias: [0]\n");
  EXPECT_NE(message_of([&] { read_calibration(path); }).find("bias"), std::string::npos) << "an unknown key";
}

// the shipped follower with its calibration section's file set
std::string follower_with_file(const std::string& dir, const std::string& file) {
  return test::config_copy(dir, "follower.yaml", {{"# file: ../calibration/panda.yaml", "file: " + file}});
}

TEST(CalibrationSection, ANodeAppliesTheFileItNamesRelativeToItsConfig) {
  const std::string dir = test::make_temp_dir();
  std::filesystem::create_directories(dir + "/calibration");
  test::write_file(dir + "/calibration/panda.yaml", calibration_text(a_fit(), "mujoco", 8));
  const ConfigNode root = ConfigNode::load_file(follower_with_file(dir, "calibration/panda.yaml"));
  const FollowerConfig applied = parse_follower_config(root);
  EXPECT_EQ(applied.calibration_file, dir + "/calibration/panda.yaml");
  EXPECT_NEAR(applied.control.calibration.payload.mass_kg, 1.1837, 1e-9);
  EXPECT_EQ(applied.calibration_plan.poses.size(), 8u);
  EXPECT_EQ(applied.calibration_plan.approach_rad, 0.05);
  const FollowerConfig ignored = parse_follower_config(root, robot::simulated_hardware(), CalibrationUse::kIgnore);
  EXPECT_EQ(ignored.control.calibration.payload.mass_kg, 0.0) << "the tool measures what the model lacks";
}

TEST(CalibrationSection, ANodeRefusesToStartWithoutItsFileButTheToolDoesNot) {
  const std::string dir = test::make_temp_dir();
  const ConfigNode root = ConfigNode::load_file(follower_with_file(dir, "calibration/panda.yaml"));
  const std::string missing = message_of([&] { parse_follower_config(root); });
  EXPECT_NE(missing.find("follower.calibration.file"), std::string::npos) << missing;
  EXPECT_NE(missing.find("does not exist: teleop_calibrate"), std::string::npos) << missing;
  EXPECT_NO_THROW(parse_follower_config(root, robot::simulated_hardware(), CalibrationUse::kIgnore));
}

TEST(CalibrationSection, OnePoseCannotSeparateAPayloadFromABias) {
  ConfigNode root = ConfigNode::load_file(test::source("config/nodes/follower.yaml"));
  root.apply_override("follower.calibration.poses=[{q_rad: [0, -0.785, 0, -2.356, 0, 1.571, 0.785]}]");
  const std::string one = message_of([&] { parse_follower_config(root); });
  EXPECT_NE(one.find("poses"), std::string::npos) << one;
  EXPECT_NE(one.find("6 or more"), std::string::npos) << one;
}

}  // namespace
}  // namespace teleop::follower
