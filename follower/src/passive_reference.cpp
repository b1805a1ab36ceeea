#include "teleop/follower/passive_reference.h"

#include <Eigen/Geometry>
#include <array>

namespace teleop::follower {
namespace {

control::DriftCompensationConfig drift_config(const runtime::TdpaSettings& settings) {
  control::DriftCompensationConfig c;
  c.channels = 6;
  c.time_constant_s = settings.drift_time_constant_s;
  for (size_t i = 0; i < 3; ++i) {
    c.max_speed[i] = settings.drift_max_speed_m_per_s;
    c.max_speed[i + 3] = settings.drift_max_speed_rad_per_s;
    c.contact_force[i] = settings.drift_contact_force_n;
    c.contact_force[i + 3] = settings.drift_contact_torque_nm;
  }
  return c;
}

}  // namespace

PassiveReference::PassiveReference(runtime::TdpaLink& link, double cycle_s,
                                   const runtime::TdpaSettings& settings)
    : link_(&link), h_(cycle_s), drift_(drift_config(settings)) {}

void PassiveReference::apply(const ValidCommand& command, const control::Vector6& wrench, ValidCommand& corrected) {
  corrected = command;
  std::array<double, 6> f{};
  std::array<double, 6> v_requested{};
  std::array<double, 6> v_out{};
  // the port's force is what crosses the channel back to the leader: the estimated external
  // wrench (the environment on the robot), positive along v when the environment pushes with it
  for (size_t i = 0; i < 6; ++i) f[i] = wrench[static_cast<Eigen::Index>(i)];
  for (size_t i = 0; i < 6; ++i) v_requested[i] = drift_.request(i, command.twist_des[i], f[i]);
  (void)link_->update(f, v_requested, v_out);
  link_->publish();
  for (size_t i = 0; i < 6; ++i) {
    drift_.account(i, command.twist_des[i], v_out[i], h_);
    corrected.twist_des[i] = v_out[i];
  }
  for (size_t i = 0; i < 3; ++i) corrected.x_des_m[i] += drift_.drift(i);
  const Eigen::Vector3d rotation(drift_.drift(3), drift_.drift(4), drift_.drift(5));
  if (rotation.norm() > 0) {
    const Eigen::Quaterniond q_in(command.orientation_wxyz[0], command.orientation_wxyz[1], command.orientation_wxyz[2],
                                  command.orientation_wxyz[3]);
    const Eigen::Quaterniond q_out = Eigen::Quaterniond(Eigen::AngleAxisd(rotation.norm(), rotation.normalized())) * q_in;
    corrected.orientation_wxyz = {q_out.w(), q_out.x(), q_out.y(), q_out.z()};
  }
}

void PassiveReference::reset() { link_->reset(); }

double PassiveReference::position_drift_m() const {
  return Eigen::Vector3d(drift_.drift(0), drift_.drift(1), drift_.drift(2)).norm();
}

double PassiveReference::rotation_drift_rad() const {
  return Eigen::Vector3d(drift_.drift(3), drift_.drift(4), drift_.drift(5)).norm();
}

}  // namespace teleop::follower
