// Payload identification on the Panda's model (control/payload_identification.h): the joint
// torques of a known payload and bias at a few poses give them back; poses that cannot tell the
// parameters apart are refused. The payload's torque is checked against MuJoCo's own: the same
// arm with the payload's body added, its gravity torque less the bare arm's.
#include <gtest/gtest.h>

#include <stdexcept>

#include "control_test_util.h"
#include "teleop/control/payload_identification.h"
#include "teleop/sim/model_additions.h"

namespace teleop::control {
namespace {

std::vector<JointVector> poses() {
  std::vector<JointVector> q(6, test::ready_q());
  q[1][6] = -0.785;
  q[2][4] = 1.2;
  q[3][4] = -1.2;
  q[4] << 0, -0.3, 0, -2.0, 0, 2.5, 0.785;
  q[5] << 0.5, -0.5, 0, -1.8, 1.5, 1.2, 0;
  return q;
}

Payload tool() {
  Payload p;
  p.mass_kg = 1.2;
  p.com_m = Eigen::Vector3d(0.02, -0.01, 0.06);
  return p;
}

TEST(PayloadTorque, IsWhatMujocoComputesForTheSameBody) {
  sim::MujocoModel bare = test::panda();
  // ee_site sits at (0 0 0.107) in link7 without rotation: the centre of mass is there plus com
  const sim::MujocoModel loaded = sim::load_with_additions(
      test::panda_path(), {{"link7", R"(<body pos="0.02 -0.01 0.167"><inertial pos="0 0 0" mass="1.2" diaginertia="1e-4 1e-4 1e-4"/></body>)"}});
  ArmDynamics with(loaded.model(), "ee_site");
  ArmDynamics without(bare.model(), "ee_site");
  for (const JointVector& q : poses()) {
    ArmState s;
    s.q = q;
    with.update(s);
    without.update(s);
    // the weight pulls on the arm: gravity torque (what holds it up) grows by -J^T w (to the
    // compiler's rounding of the added body: 1e-5 Nm)
    const JointVector expected = -(with.gravity() - without.gravity());
    EXPECT_LT((payload_torque(without, tool()) - expected).cwiseAbs().maxCoeff(), 1e-4) << payload_torque(without, tool()).transpose()
                                                                          << "\n" << expected.transpose();
  }
}

TEST(PayloadIdentification, RecoversAKnownPayloadAndBiasExactly) {
  const sim::MujocoModel model = test::panda();
  ArmDynamics dynamics(model.model(), "ee_site");
  JointVector bias;
  bias << 0.3, -0.2, 0.1, 0.25, -0.05, 0.04, -0.02;
  std::vector<PayloadSample> samples;
  for (const JointVector& q : poses()) {
    ArmState s;
    s.q = q;
    dynamics.update(s);
    samples.push_back({q, payload_torque(dynamics, tool()) + bias});
  }
  const PayloadFit fit = identify_payload(dynamics, samples);
  EXPECT_NEAR(fit.calibration.payload.mass_kg, 1.2, 1e-9);
  EXPECT_TRUE(fit.calibration.payload.com_m.isApprox(tool().com_m, 1e-9)) << fit.calibration.payload.com_m.transpose();
  EXPECT_TRUE(fit.calibration.torque_bias_nm.isApprox(bias, 1e-9)) << fit.calibration.torque_bias_nm.transpose();
  EXPECT_LT(fit.residual_rms_nm, 1e-9);
  EXPECT_GT(fit.conditioning, 1e-3);
}

TEST(PayloadIdentification, RefusesTooFewOrIndistinguishablePoses) {
  const sim::MujocoModel model = test::panda();
  ArmDynamics dynamics(model.model(), "ee_site");
  const JointVector tau = JointVector::Zero();
  EXPECT_THROW(identify_payload(dynamics, {{test::ready_q(), tau}}), std::invalid_argument);
  // one pose twice: the bias and the payload's torque there are one and the same
  EXPECT_THROW(identify_payload(dynamics, {{test::ready_q(), tau}, {test::ready_q(), tau}}), std::invalid_argument);
}

}  // namespace
}  // namespace teleop::control
