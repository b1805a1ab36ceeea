#include "cartesian_mapping.h"

#include <algorithm>

namespace teleop::leader {

void CartesianMapping::start(const Eigen::Vector3d& x_device, const Eigen::Matrix3d& r_device,
                             const Eigen::Vector3d& x_home, const Eigen::Matrix3d& r_home) {
  x_ref_device_ = x_device;
  r_ref_device_ = r_device;
  x_ref_cmd_ = x_cmd_ = x_home;
  r_ref_cmd_ = r_cmd_ = r_home;
  twist_.setZero();
  frozen_ = false;
}

void CartesianMapping::map(const Eigen::Vector3d& x_device, const Eigen::Matrix3d& r_device,
                           const control::Vector6& twist_device, bool frozen) {
  if (frozen) {
    frozen_ = true;
    twist_.setZero();
    return;
  }
  if (frozen_) {
    // released: continue from the held command and where the device is now
    x_ref_device_ = x_device;
    r_ref_device_ = r_device;
    x_ref_cmd_ = x_cmd_;
    r_ref_cmd_ = r_cmd_;
    frozen_ = false;
  }
  x_cmd_ = x_ref_cmd_ + scale_ * (x_device - x_ref_device_);
  r_cmd_ = r_device * r_ref_device_.transpose() * r_ref_cmd_;
  twist_.head<3>() = scale_ * twist_device.head<3>();
  twist_.tail<3>() = twist_device.tail<3>();
  keep_in_box();
}

// a component outside the box stops at its wall, and its reference moves with the device: motion
// back into the box acts at once instead of first undoing what was pushed past the wall
void CartesianMapping::keep_in_box() {
  if (!box_) return;
  bool outside = false;
  for (int i = 0; i < 3; ++i) {
    const double bounded = std::clamp(x_cmd_[i], box_->first[i], box_->second[i]);
    if (bounded == x_cmd_[i]) continue;
    x_ref_cmd_[i] += bounded - x_cmd_[i];
    x_cmd_[i] = bounded;
    twist_[i] = 0.0;
    outside = true;
  }
  if (outside) ++box_saturations_;
}

}  // namespace teleop::leader
