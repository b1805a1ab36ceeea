#include "teleop/control/arm_dynamics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "allocation_counter.h"
#include "control_test_util.h"

namespace teleop::control {
namespace {

using test::panda;

TEST(ArmDynamics, MatchesTheSimulationWhenGivenItsState) {
  auto sim = panda();
  const mjModel* m = sim.model();
  mjData* d = sim.data();
  ArmDynamics dyn(m, "ee_site");
  JointVector dq;
  dq << 0.3, -0.2, 0.5, 0.1, -0.4, 0.6, 0.2;
  for (int i = 0; i < kDof; ++i) d->qvel[i] = dq[i];
  d->qpos[1] += 0.2;
  mj_forward(m, d);
  const ArmState s = test::state_of(d);
  dyn.update(s);

  JointMatrix full;
  mj_fullM(m, full.data(), d->qM);
  EXPECT_LT((dyn.mass() - full).norm(), 1e-12);
  EXPECT_GT(dyn.mass()(6, 6), m->dof_armature[6]);  // armature included
  for (int i = 0; i < kDof; ++i) EXPECT_NEAR(dyn.bias()[i], d->qfrc_bias[i], 1e-10) << i;
  const int site = sim.site_id("ee_site");
  for (int r = 0; r < 3; ++r) EXPECT_NEAR(dyn.ee_position()[r], d->site_xpos[3 * site + r], 1e-12);
  Eigen::Matrix<double, 3, kDof, Eigen::RowMajor> jacp;
  mj_jacSite(m, d, jacp.data(), nullptr, site);
  EXPECT_LT((dyn.jacobian().topRows<3>() - jacp).norm(), 1e-12);

  // gravity alone = the bias at rest
  for (int i = 0; i < kDof; ++i) d->qvel[i] = 0;
  mj_forward(m, d);
  for (int i = 0; i < kDof; ++i) EXPECT_NEAR(dyn.gravity()[i], d->qfrc_bias[i], 1e-10) << i;
  EXPECT_GT(dyn.gravity().norm(), 1.0);
}

TEST(ArmDynamics, LeavesTheSimulationDataUntouchedWhenUpdated) {
  auto sim = panda();
  const mjModel* m = sim.model();
  mjData* d = sim.data();
  d->qvel[2] = 0.4;
  mj_forward(m, d);
  const std::vector<mjtNum> qpos(d->qpos, d->qpos + m->nq);
  const std::vector<mjtNum> qm(d->qM, d->qM + m->nM);
  const std::vector<mjtNum> xpos(d->site_xpos, d->site_xpos + 3 * m->nsite);
  ArmDynamics dyn(m, "ee_site");
  ArmState other;
  other.q = test::ready_q() + JointVector::Constant(0.3);
  other.dq = JointVector::Constant(-0.5);
  dyn.update(other);
  EXPECT_EQ(qpos, std::vector<mjtNum>(d->qpos, d->qpos + m->nq));
  EXPECT_EQ(qm, std::vector<mjtNum>(d->qM, d->qM + m->nM));
  EXPECT_EQ(xpos, std::vector<mjtNum>(d->site_xpos, d->site_xpos + 3 * m->nsite));
  EXPECT_EQ(d->qvel[2], 0.4);
}

TEST(ArmDynamics, ThrowsWhenTheModelIsNotOneSevenJointArm) {
  auto two_arms = sim::MujocoModel::load(std::string(TELEOP_SOURCE_DIR) + "/config/models/dual_arm.xml");
  EXPECT_THROW(ArmDynamics(two_arms.model(), "left_ee_site"), std::invalid_argument);
}

TEST(ArmDynamics, ThrowsWhenTheSiteIsMissing) {
  auto sim = panda();
  EXPECT_THROW(ArmDynamics(sim.model(), "no_such_site"), std::invalid_argument);
}

TEST(ArmDynamics, DoesNotAllocateWhenUpdated) {
  auto sim = panda();
  ArmDynamics dyn(sim.model(), "ee_site");
  ArmState s = test::state_of(sim.data());
  dyn.update(s);
  double sum = 0;
  {
    teleop::test::ScopedAllocationCounter counter;
    for (int k = 0; k < 1000; ++k) {
      s.q[0] = 0.001 * k;
      s.dq[3] = 0.002 * k;
      dyn.update(s);
      sum += dyn.mass()(0, 0) + dyn.bias()[3] + dyn.jacobian()(0, 0);
    }
    EXPECT_EQ(counter.count(), 0u);
  }
  EXPECT_TRUE(std::isfinite(sum));
}

}  // namespace
}  // namespace teleop::control
