#include "teleop/follower/passive_reference.h"

#include <Eigen/Geometry>
#include <array>

namespace teleop::follower {

void PassiveReference::apply(const ValidCommand& command, const control::Vector6& pose_error, ValidCommand& corrected) {
  corrected = command;
  std::array<double, 6> f{};
  std::array<double, 6> v{};
  std::array<double, 6> v_out{};
  for (size_t i = 0; i < 3; ++i) {
    // the spring K e pulls the robot towards the reference and the reference back with -K e
    f[i] = -command.translational_stiffness_n_per_m[i] * pose_error[static_cast<Eigen::Index>(i)];
    f[i + 3] = -command.rotational_stiffness_nm_per_rad[i] * pose_error[static_cast<Eigen::Index>(i + 3)];
  }
  std::copy(command.twist_des.begin(), command.twist_des.end(), v.begin());
  (void)link_->update(f, v, v_out);
  link_->publish();
  for (size_t i = 0; i < 6; ++i) {
    drift_[static_cast<Eigen::Index>(i)] += (v_out[i] - v[i]) * h_;
    corrected.twist_des[i] = v_out[i];
  }
  for (size_t i = 0; i < 3; ++i) corrected.x_des_m[i] += drift_[static_cast<Eigen::Index>(i)];
  const Eigen::Vector3d rotation = drift_.tail<3>();
  if (rotation.norm() > 0) {
    const Eigen::Quaterniond q_in(command.orientation_wxyz[0], command.orientation_wxyz[1], command.orientation_wxyz[2],
                                  command.orientation_wxyz[3]);
    const Eigen::Quaterniond q_out = Eigen::Quaterniond(Eigen::AngleAxisd(rotation.norm(), rotation.normalized())) * q_in;
    corrected.orientation_wxyz = {q_out.w(), q_out.x(), q_out.y(), q_out.z()};
  }
}

void PassiveReference::reset() {
  link_->reset();
  drift_.setZero();
}

}  // namespace teleop::follower
