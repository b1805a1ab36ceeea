#pragma once
// The leader device's end-effector pose mapped into the follower's workspace: positions scaled
// about where the device started, rotations applied as the device's rotation since then,
//   x_cmd = x_home + s (x - x_0),   R_cmd = (R R_0^T) R_home,   twist_cmd = (s v, w).
// While frozen (clutch pressed, follower lost) the command holds and the device moves freely; on
// release the references are re-taken, so the follower continues from where it was told to stop.
// Bounded, the command's position stays in a box of the base frame.

#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <utility>

#include "teleop/control/types.h"

namespace teleop::leader {

class CartesianMapping {
 public:
  explicit CartesianMapping(double scale) : scale_(scale) {}

  /// Keeps the command's position within [min, max] (base frame). Setup time.
  void bound(const Eigen::Vector3d& min, const Eigen::Vector3d& max) { box_.emplace(min, max); }

  /// The device's pose at the start and the follower's home pose it stands for.
  void start(const Eigen::Vector3d& x_device, const Eigen::Matrix3d& r_device, const Eigen::Vector3d& x_home,
             const Eigen::Matrix3d& r_home);
  /// One cycle. Real-time safe.
  void map(const Eigen::Vector3d& x_device, const Eigen::Matrix3d& r_device, const control::Vector6& twist_device,
           bool frozen);

  const Eigen::Vector3d& position() const { return x_cmd_; }
  Eigen::Quaterniond orientation() const { return Eigen::Quaterniond(r_cmd_); }
  /// Linear then angular velocity of the command; zero while frozen.
  const control::Vector6& twist() const { return twist_; }
  double scale() const { return scale_; }
  /// Cycles in which the command was held at a wall of its box.
  uint64_t box_saturations() const { return box_saturations_; }

 private:
  void keep_in_box();

  double scale_;
  bool frozen_ = false;
  Eigen::Vector3d x_ref_device_ = Eigen::Vector3d::Zero();
  Eigen::Matrix3d r_ref_device_ = Eigen::Matrix3d::Identity();
  Eigen::Vector3d x_ref_cmd_ = Eigen::Vector3d::Zero();
  Eigen::Matrix3d r_ref_cmd_ = Eigen::Matrix3d::Identity();
  Eigen::Vector3d x_cmd_ = Eigen::Vector3d::Zero();
  Eigen::Matrix3d r_cmd_ = Eigen::Matrix3d::Identity();
  control::Vector6 twist_ = control::Vector6::Zero();
  std::optional<std::pair<Eigen::Vector3d, Eigen::Vector3d>> box_;
  uint64_t box_saturations_ = 0;
};

}  // namespace teleop::leader
