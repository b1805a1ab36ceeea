#include "teleop/control/arm_dynamics.h"

#include <stdexcept>
#include <string>

namespace teleop::control {

ArmDynamics::ArmDynamics(const mjModel* model, std::string_view ee_site) : model_(model) {
  if (model == nullptr || model->nv != kDof || model->nq != kDof) {
    throw std::invalid_argument("ArmDynamics: the model must have exactly " + std::to_string(kDof) +
                                " hinge degrees of freedom");
  }
  const std::string name(ee_site);
  site_ = mj_name2id(model, mjOBJ_SITE, name.c_str());
  if (site_ < 0) throw std::invalid_argument("ArmDynamics: the model has no site '" + name + "'");
  data_.reset(mj_makeData(model));
  if (!data_) throw std::runtime_error("ArmDynamics: mj_makeData failed");
}

void ArmDynamics::update(const ArmState& state) {
  if (valid_ && state.q == state_.q && state.dq == state_.dq) return;
  const mjModel* m = model_;
  mjData* d = data_.get();
  for (int i = 0; i < kDof; ++i) {
    d->qpos[i] = state.q[i];
    d->qvel[i] = 0;
  }
  mj_kinematics(m, d);
  mj_comPos(m, d);
  mj_crb(m, d);  // qM, with dof_armature added to its diagonal

  // gravity alone: the RNE bias at zero velocity
  mj_comVel(m, d);
  mj_rne(m, d, 0, gravity_.data());
  for (int i = 0; i < kDof; ++i) d->qvel[i] = state.dq[i];
  mj_comVel(m, d);
  mj_rne(m, d, 0, bias_.data());

  // MuJoCo's dense matrices are row-major; M is symmetric, so the column-major copy is M itself
  mj_fullM(m, mass_.data(), d->qM);

  Eigen::Matrix<double, 3, kDof, Eigen::RowMajor> jacp;
  Eigen::Matrix<double, 3, kDof, Eigen::RowMajor> jacr;
  mj_jacSite(m, d, jacp.data(), jacr.data(), site_);
  jacobian_.topRows<3>() = jacp;
  jacobian_.bottomRows<3>() = jacr;

  for (int r = 0; r < 3; ++r) {
    ee_position_[r] = d->site_xpos[3 * site_ + r];
    for (int c = 0; c < 3; ++c) ee_rotation_(r, c) = d->site_xmat[9 * site_ + 3 * r + c];
  }
  state_ = state;
  valid_ = true;
}

}  // namespace teleop::control
