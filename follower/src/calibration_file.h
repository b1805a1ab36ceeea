#pragma once
// A robot's calibration as a file (docs/calibration.md): the payload on its flange and the bias
// of its external-torque estimate, written by teleop_calibrate and applied by the follower at
// start (`follower.calibration.file`).

#include <string>

#include "teleop/control/payload.h"
#include "teleop/common/config.h"
#include "teleop/control/payload_identification.h"
#include "teleop/follower/payload_calibration.h"

namespace teleop::follower {

/// Reads `path`. Throws ConfigError naming the file, the key and the problem.
control::ArmCalibration read_calibration(const std::string& path);

// the `follower.calibration` section
/// `file`, relative to the config's folder ("" when absent); it need not exist yet.
std::string calibration_file_of(const ConfigNode& section);
/// The poses (`poses: [{q_rad: [...]}, ...]`) and times teleop_calibrate drives.
PayloadCalibrationPlan read_calibration_plan(const ConfigNode& section);
/// The file's calibration, for a node to apply; a missing file is an error naming the key and
/// the tool that writes it.
control::ArmCalibration applied_calibration(const ConfigNode& section, const std::string& path);

/// The file's text: the fit's result, and how good it was (residual, conditioning, poses) and of
/// which robot, for whoever reads it later.
std::string calibration_text(const control::PayloadFit& fit, const std::string& robot, size_t poses);

}  // namespace teleop::follower
