#include "cartesian_mapping.h"

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
}

}  // namespace teleop::leader
