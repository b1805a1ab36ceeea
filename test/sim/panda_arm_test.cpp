// The single arm (config/models/panda.xml, i.e. templates/panda_chain.xml.in) against the numbers
// it cites: Franka's DH table and data-sheet limits, Gaz et al.'s identified dynamic parameters.
// The reference values are typed in here again from the sources, on purpose.

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <random>
#include <string>

#include "sim_test_util.h"
#include "teleop/sim/mujoco_model.h"

namespace teleop::sim {
namespace {

using test::model_path;

constexpr int kJoints = 7;
using Joints = std::array<double, kJoints>;

// Franka Emika, "Robot and interface specifications", Limits for Panda
constexpr Joints kQMin{-2.8973, -1.7628, -2.8973, -3.0718, -2.8973, -0.0175, -2.8973};
constexpr Joints kQMax{2.8973, 1.7628, 2.8973, -0.0698, 2.8973, 3.7525, 2.8973};
constexpr Joints kTauMax{87, 87, 87, 87, 12, 12, 12};

// Franka Emika, "Robot and interface specifications", Denavit-Hartenberg parameters (Craig):
// per joint a [m], d [m], alpha [rad]; then the flange
struct DhRow {
  double a, d, alpha;
};
constexpr std::array<DhRow, kJoints> kDh{{{0, 0.333, 0},
                                          {0, 0, -M_PI / 2},
                                          {0, 0.316, M_PI / 2},
                                          {0.0825, 0, M_PI / 2},
                                          {-0.0825, 0.384, -M_PI / 2},
                                          {0, 0, M_PI / 2},
                                          {0.088, 0, M_PI / 2}}};
constexpr DhRow kFlange{0, 0.107, 0};

// Gaz et al. 2019 (RA-L), supplementary tables VIII and IX: link masses [kg], CoMs [m] in the link
// frame, inertia tensors [kg m^2] about the CoM as Ixx Ixy Ixz Iyy Iyz Izz; friction phi1 [Nm]
constexpr Joints kMass{4.970684, 0.646926, 3.228604, 3.587895, 1.225946, 1.666555, 0.735522};
constexpr std::array<std::array<double, 3>, kJoints> kCom{{{3.875e-3, 2.081e-3, -4.762e-2},
                                                           {-3.141e-3, -2.872e-2, 3.495e-3},
                                                           {2.7518e-2, 3.9252e-2, -6.6502e-2},
                                                           {-5.317e-2, 1.04419e-1, 2.7454e-2},
                                                           {-1.1953e-2, 4.1065e-2, -3.8437e-2},
                                                           {6.0149e-2, -1.4117e-2, -1.0517e-2},
                                                           {1.0517e-2, -4.252e-3, 6.1597e-2}}};
constexpr std::array<std::array<double, 6>, kJoints> kInertia{
    {{7.0337e-01, -1.3900e-04, 6.7720e-03, 7.0661e-01, 1.9169e-02, 9.1170e-03},
     {7.9620e-03, -3.9250e-03, 1.0254e-02, 2.8110e-02, 7.0400e-04, 2.5995e-02},
     {3.7242e-02, -4.7610e-03, -1.1396e-02, 3.6155e-02, -1.2805e-02, 1.0830e-02},
     {2.5853e-02, 7.7960e-03, -1.3320e-03, 1.9552e-02, 8.6410e-03, 2.8323e-02},
     {3.5549e-02, -2.1170e-03, -4.0370e-03, 2.9474e-02, 2.2900e-04, 8.6270e-03},
     {1.9640e-03, 1.0900e-04, -1.1580e-03, 4.3540e-03, 3.4100e-04, 5.4330e-03},
     {1.2516e-02, -4.2800e-04, -1.1960e-03, 1.0027e-02, -7.4100e-04, 4.8150e-03}}};
constexpr Joints kPhi1{0.54615, 0.87224, 0.64068, 1.2794, 0.83904, 0.30301, 0.56489};
// franka_ros franka_description inertial.yaml: the base link, not identified by Gaz et al.
constexpr double kLink0Mass = 0.629769;

constexpr Joints kReady{0, -M_PI / 4, 0, -3 * M_PI / 4, 0, M_PI / 2, M_PI / 4};

Eigen::Isometry3d dh_step(const DhRow& row, double q) {
  return Eigen::Isometry3d(Eigen::AngleAxisd(row.alpha, Eigen::Vector3d::UnitX())) * Eigen::Translation3d(row.a, 0, 0) *
         Eigen::AngleAxisd(q, Eigen::Vector3d::UnitZ()) * Eigen::Translation3d(0, 0, row.d);
}

// flange pose in the base frame from the DH table alone
Eigen::Isometry3d dh_flange(const Joints& q) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  for (int i = 0; i < kJoints; ++i) t = t * dh_step(kDh[i], q[i]);
  return t * dh_step(kFlange, 0);
}

class PandaArm : public ::testing::Test {
 protected:
  void SetUp() override {
    for (int i = 0; i < kJoints; ++i) {
      joint_[i] = sim_.joint_id("joint" + std::to_string(i + 1));
      body_[i] = sim_.body_id("link" + std::to_string(i + 1));
    }
  }
  void set_q(const Joints& q) {
    for (int i = 0; i < kJoints; ++i) sim_.data()->qpos[m()->jnt_qposadr[joint_[i]]] = q[i];
    mj_kinematics(m(), sim_.data());
  }
  const mjModel* m() const { return sim_.model(); }

  MujocoModel sim_ = MujocoModel::load(model_path("panda.xml"));
  std::array<int, kJoints> joint_{};
  std::array<int, kJoints> body_{};
};

TEST_F(PandaArm, HasSevenHingeJointsWithDataSheetRangesWhenLoaded) {
  ASSERT_EQ(m()->njnt, kJoints);
  ASSERT_EQ(m()->nv, kJoints);
  for (int i = 0; i < kJoints; ++i) {
    SCOPED_TRACE(i);
    EXPECT_EQ(m()->jnt_type[joint_[i]], mjJNT_HINGE);
    EXPECT_TRUE(m()->jnt_limited[joint_[i]]);
    EXPECT_DOUBLE_EQ(m()->jnt_range[2 * joint_[i]], kQMin[i]);
    EXPECT_DOUBLE_EQ(m()->jnt_range[2 * joint_[i] + 1], kQMax[i]);
  }
}

TEST_F(PandaArm, HasJointTorqueMotorsLimitedToDataSheetTorquesWhenLoaded) {
  ASSERT_EQ(m()->nu, kJoints);
  for (int i = 0; i < kJoints; ++i) {
    SCOPED_TRACE(i);
    const int a = sim_.actuator_id("motor" + std::to_string(i + 1));
    EXPECT_EQ(m()->actuator_trntype[a], mjTRN_JOINT);
    EXPECT_EQ(m()->actuator_trnid[2 * a], joint_[i]);
    EXPECT_EQ(m()->actuator_gaintype[a], mjGAIN_FIXED);
    EXPECT_EQ(m()->actuator_biastype[a], mjBIAS_NONE);
    EXPECT_DOUBLE_EQ(m()->actuator_gear[6 * a], 1.0);
    EXPECT_DOUBLE_EQ(m()->actuator_gainprm[mjNGAIN * a], 1.0);
    EXPECT_TRUE(m()->actuator_ctrllimited[a]);
    EXPECT_DOUBLE_EQ(m()->actuator_ctrlrange[2 * a], -kTauMax[i]);
    EXPECT_DOUBLE_EQ(m()->actuator_ctrlrange[2 * a + 1], kTauMax[i]);
  }
}

TEST_F(PandaArm, WeighsTheSumOfTheCitedLinkMassesWhenLoaded) {
  double links = 0;
  for (int i = 0; i < kJoints; ++i) {
    EXPECT_DOUBLE_EQ(m()->body_mass[body_[i]], kMass[i]) << "link" << i + 1;
    links += kMass[i];
  }
  EXPECT_DOUBLE_EQ(m()->body_mass[sim_.body_id("link0")], kLink0Mass);
  double total = 0;
  for (int b = 0; b < m()->nbody; ++b) total += m()->body_mass[b];
  EXPECT_NEAR(total, kLink0Mass + links, 1e-12);
  EXPECT_NEAR(links, 16.062132, 1e-9);
}

TEST_F(PandaArm, PlacesIdentifiedCentresOfMassAndInertiasInTheLinkFramesWhenLoaded) {
  for (int i = 0; i < kJoints; ++i) {
    SCOPED_TRACE(i);
    const int b = body_[i];
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(m()->body_ipos[3 * b + k], kCom[i][k], 1e-12);
    // MuJoCo keeps principal axes and moments: rebuild the tensor in link axes
    const Eigen::Quaterniond axes(m()->body_iquat[4 * b], m()->body_iquat[4 * b + 1], m()->body_iquat[4 * b + 2],
                                  m()->body_iquat[4 * b + 3]);
    const Eigen::Matrix3d principal = Eigen::Vector3d(test::vec3(m()->body_inertia + 3 * b)).asDiagonal();
    const Eigen::Matrix3d tensor = axes.toRotationMatrix() * principal * axes.toRotationMatrix().transpose();
    const auto& in = kInertia[i];
    Eigen::Matrix3d expected;
    expected << in[0], in[1], in[2], in[1], in[3], in[4], in[2], in[4], in[5];
    // to the 5 significant digits of the published values (MuJoCo's 2.2 eigensolver is good to ~1e-6)
    const double tolerance = 1e-5 * expected.cwiseAbs().maxCoeff();
    EXPECT_LT((tensor - expected).cwiseAbs().maxCoeff(), tolerance) << tensor << "\nexpected\n" << expected;
  }
}

TEST_F(PandaArm, MapsIdentifiedFrictionToCoulombFrictionLossWhenLoaded) {
  for (int i = 0; i < kJoints; ++i) {
    SCOPED_TRACE(i);
    const int dof = m()->jnt_dofadr[joint_[i]];
    EXPECT_DOUBLE_EQ(m()->dof_frictionloss[dof], kPhi1[i] / 2);  // half the sigmoid's swing
    EXPECT_DOUBLE_EQ(m()->dof_damping[dof], 0.0);                // no viscous term in the model
    EXPECT_GT(m()->dof_armature[dof], 0.0);
  }
}

TEST_F(PandaArm, RunsAtOneKilohertzWhenLoaded) { EXPECT_DOUBLE_EQ(m()->opt.timestep, 0.001); }

void expect_flange_matches_dh(const mjData* d, int site, const Joints& q) {
  const Eigen::Isometry3d expected = dh_flange(q);
  const Eigen::Isometry3d actual = test::site_pose(d, site);
  EXPECT_LT((actual.translation() - expected.translation()).norm(), 1e-9)
      << actual.translation().transpose() << " vs DH " << expected.translation().transpose();
  EXPECT_LT((actual.linear() - expected.linear()).cwiseAbs().maxCoeff(), 1e-9) << actual.linear() << "\nvs DH\n"
                                                                               << expected.linear();
}

TEST_F(PandaArm, PutsEeSiteOnTheDhFlangeWhenAtZero) {
  set_q({0, 0, 0, 0, 0, 0, 0});
  expect_flange_matches_dh(sim_.data(), sim_.site_id("ee_site"), {0, 0, 0, 0, 0, 0, 0});
  // and the numbers one reads off the table: x = a4 + a5 + a7, z = d1 + d3 + d5 - d_flange
  EXPECT_NEAR(sim_.data()->site_xpos[0], 0.088, 1e-12);
  EXPECT_NEAR(sim_.data()->site_xpos[2], 0.926, 1e-12);
}

TEST_F(PandaArm, PutsEeSiteOnTheDhFlangeWhenAtReadyPose) {
  set_q(kReady);
  expect_flange_matches_dh(sim_.data(), sim_.site_id("ee_site"), kReady);
}

TEST_F(PandaArm, PutsEeSiteOnTheDhFlangeWhenAtRandomPosesWithinLimits) {
  std::mt19937 rng(7);
  for (int n = 0; n < 50; ++n) {
    Joints q{};
    for (int i = 0; i < kJoints; ++i) q[i] = std::uniform_real_distribution<double>(kQMin[i], kQMax[i])(rng);
    set_q(q);
    SCOPED_TRACE(n);
    expect_flange_matches_dh(sim_.data(), sim_.site_id("ee_site"), q);
  }
}

// Holds `q0` for 5 s with torques = qfrc_bias computed for the state of every 1 ms step; returns
// the largest deviation of any joint from q0 seen during the run.
double hold_drift(MujocoModel& sim, const std::array<int, kJoints>& joints, const Joints& q0, bool compensate) {
  sim.reset("ready");
  for (int i = 0; i < kJoints; ++i) sim.data()->qpos[sim.model()->jnt_qposadr[joints[i]]] = q0[i];
  double drift = 0;
  auto track = [&] {
    for (int i = 0; i < kJoints; ++i) {
      drift = std::max(drift, std::abs(sim.data()->qpos[sim.model()->jnt_qposadr[joints[i]]] - q0[i]));
    }
  };
  if (compensate) {
    test::drive_site(sim, -1, Eigen::Vector3d::Zero(), 0.0, 5.0, track);
  } else {
    for (int k = 0; k < 5000; ++k) {
      mj_step(sim.model(), sim.data());
      track();
    }
  }
  return drift;
}

TEST_F(PandaArm, HoldsReadyPoseWhenTorquesEqualBiasForces) { EXPECT_LT(hold_drift(sim_, joint_, kReady, true), 1e-3); }

TEST_F(PandaArm, HoldsReadyPoseWithoutJointFrictionWhenTorquesEqualBiasForces) {
  // without friction loss nothing but the compensation holds the arm up
  sim_.model()->opt.disableflags |= mjDSBL_FRICTIONLOSS;
  EXPECT_LT(hold_drift(sim_, joint_, kReady, true), 1e-3);
  EXPECT_GT(hold_drift(sim_, joint_, kReady, false), 0.1);  // and without it the arm falls
}

TEST_F(PandaArm, HoldsOtherPosesWhenTorquesEqualBiasForces) {
  sim_.model()->opt.disableflags |= mjDSBL_FRICTIONLOSS;
  EXPECT_LT(hold_drift(sim_, joint_, {0.5, 0.3, -0.4, -1.8, 0.6, 2.2, -0.3}, true), 1e-3);
  EXPECT_LT(hold_drift(sim_, joint_, {-1.0, 1.0, 1.0, -0.6, -1.0, 0.8, 1.5}, true), 1e-3);
}

}  // namespace
}  // namespace teleop::sim
