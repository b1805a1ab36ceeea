#include "teleop/control/payload.h"

namespace teleop::control {
namespace {

Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

Eigen::Vector3d gravity_of(const mjModel* model) { return Eigen::Vector3d(model->opt.gravity[0], model->opt.gravity[1], model->opt.gravity[2]); }

}  // namespace

Eigen::Matrix<double, 6, 4> payload_wrench_map(const Eigen::Matrix3d& site_rotation, const Eigen::Vector3d& gravity) {
  // force m g at the centre of mass R c from the site: moment (R m c) x g = -[g]x R (m c)
  Eigen::Matrix<double, 6, 4> map = Eigen::Matrix<double, 6, 4>::Zero();
  map.block<3, 1>(0, 0) = gravity;
  map.block<3, 3>(3, 1) = -cross_matrix(gravity) * site_rotation;
  return map;
}

JointVector payload_torque(const ArmDynamics& dynamics, const Payload& payload) {
  Eigen::Vector4d phi;
  phi << payload.mass_kg, payload.mass_kg * payload.com_m;
  return dynamics.jacobian().transpose() * (payload_wrench_map(dynamics.ee_rotation(), gravity_of(dynamics.model())) * phi);
}

}  // namespace teleop::control
