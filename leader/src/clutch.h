#pragma once
// Workspace scaling and indexing between the leader device and the follower's command:
//   command = command_ref + scale * (device - device_ref)
// While the clutch is pressed the command freezes and the device moves freely; on release the
// references are re-taken (device_ref = device now, command_ref = the frozen command), so the
// operator re-indexes without moving the follower and without a jump. Works on any vector of
// positions (joint angles, or a Cartesian position).

#include <cstddef>

#include "teleop/common/joint_model.h"

namespace teleop::leader {

class Clutch {
 public:
  Clutch(size_t size, double scale) : size_(size), scale_(scale) {}

  /// Takes the first device position as the reference; the command starts at `command_start`.
  void start(const JointVector& device, const JointVector& command_start);
  /// One cycle: returns the command for the device position `device`. Real-time safe.
  const JointVector& map(const JointVector& device, bool pressed);

  bool pressed() const { return pressed_; }
  const JointVector& command() const { return command_; }

 private:
  size_t size_;
  double scale_;
  bool pressed_ = false;
  JointVector device_ref_{};
  JointVector command_ref_{};
  JointVector command_{};
};

}  // namespace teleop::leader
