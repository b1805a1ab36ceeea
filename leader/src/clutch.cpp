#include "clutch.h"

namespace teleop::leader {

void Clutch::start(const JointVector& device, const JointVector& command_start) {
  device_ref_ = device;
  command_ref_ = command_start;
  command_ = command_start;
  pressed_ = false;
}

const JointVector& Clutch::map(const JointVector& device, bool pressed) {
  if (pressed) {
    pressed_ = true;
    return command_;  // frozen
  }
  if (pressed_) {
    // released: continue from here, where the device and the command are now
    device_ref_ = device;
    command_ref_ = command_;
    pressed_ = false;
  }
  for (size_t i = 0; i < size_; ++i) command_[i] = command_ref_[i] + scale_ * (device[i] - device_ref_[i]);
  return command_;
}

}  // namespace teleop::leader
