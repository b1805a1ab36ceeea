#include "teleop/control/payload_identification.h"

#include <Eigen/SVD>
#include <cmath>
#include <stdexcept>

namespace teleop::control {
namespace {

constexpr int kParameters = 4 + kDof;  // m, m c, then the bias of each joint

// the rows of one pose: tau_ext = [J^T W, I] (m, m c, b)
Eigen::Matrix<double, kDof, kParameters> pose_rows(ArmDynamics& dynamics, const JointVector& q) {
  ArmState state;
  state.q = q;
  dynamics.update(state);
  const mjModel* m = dynamics.model();
  const Eigen::Vector3d gravity(m->opt.gravity[0], m->opt.gravity[1], m->opt.gravity[2]);
  Eigen::Matrix<double, kDof, kParameters> rows;
  rows.leftCols<4>() = dynamics.jacobian().transpose() * payload_wrench_map(dynamics.ee_rotation(), gravity);
  rows.rightCols<kDof>().setIdentity();
  return rows;
}

}  // namespace

PayloadFit identify_payload(ArmDynamics& dynamics, const std::vector<PayloadSample>& samples) {
  if (samples.size() < 2) throw std::invalid_argument("payload identification needs at least 2 poses");
  const Eigen::Index n = static_cast<Eigen::Index>(samples.size()) * kDof;
  Eigen::MatrixXd regressor(n, kParameters);
  Eigen::VectorXd measured(n);
  for (size_t k = 0; k < samples.size(); ++k) {
    const Eigen::Index row = static_cast<Eigen::Index>(k) * kDof;
    regressor.middleRows<kDof>(row) = pose_rows(dynamics, samples[k].q);
    measured.segment<kDof>(row) = samples[k].tau_ext_nm;
  }
  // columns scaled to unit norm, so that the conditioning compares parameters of unlike units
  const Eigen::VectorXd scale = regressor.colwise().norm().cwiseMax(1e-12).cwiseInverse();
  const Eigen::MatrixXd scaled = regressor * scale.asDiagonal();
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(scaled, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Eigen::VectorXd sv = svd.singularValues();
  PayloadFit fit;
  fit.conditioning = sv(sv.size() - 1) / sv(0);
  if (fit.conditioning < 1e-6) {
    throw std::invalid_argument("the poses leave the payload undetermined (conditioning " + std::to_string(fit.conditioning) +
                                "): turn the flange through gravity about more axes");
  }
  const Eigen::VectorXd parameters = scale.asDiagonal() * svd.solve(measured);
  Payload& payload = fit.calibration.payload;
  payload.mass_kg = parameters(0);
  payload.com_m = std::abs(payload.mass_kg) > 1e-6 ? Eigen::Vector3d(parameters.segment<3>(1) / payload.mass_kg)
                                                   : Eigen::Vector3d::Zero();
  fit.calibration.torque_bias_nm = parameters.tail<kDof>();
  fit.residual_rms_nm = std::sqrt((regressor * parameters - measured).squaredNorm() / static_cast<double>(n));
  return fit;
}

}  // namespace teleop::control
