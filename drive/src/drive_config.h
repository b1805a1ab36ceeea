#pragma once
// The checks an EmulatedDriveConfig passes before a drive is built from it.

#include "teleop/drive/emulated_drive.h"

namespace teleop::drive {

/// Throws std::invalid_argument naming the first problem: a node id outside 1..127, motor or
/// controller parameters that are not physical, inconsistent current limits.
void validate(const EmulatedDriveConfig& config);

}  // namespace teleop::drive
