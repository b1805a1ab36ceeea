// The UR5-class arm of the SVH study's scene (config/models/parts/ur5_chain.xml) against UR's
// published standard DH parameters, masses and limits, through an independent Eigen DH chain.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <random>
#include <string>

#include "sim_test_util.h"
#include "teleop/sim/mujoco_model.h"

namespace teleop::sim {
namespace {

constexpr int kJoints = 6;
const std::array<std::string, kJoints> kNames = {"shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint",
                                                 "wrist_1_joint",      "wrist_2_joint",       "wrist_3_joint"};

// standard DH of the UR5 (CB3): Rz(q) Tz(d) Tx(a) Rx(alpha)
struct DhRow {
  double a, d, alpha;
};
constexpr std::array<DhRow, kJoints> kDh{{{0, 0.089159, M_PI / 2},
                                          {-0.425, 0, 0},
                                          {-0.39225, 0, 0},
                                          {0, 0.10915, M_PI / 2},
                                          {0, 0.09465, -M_PI / 2},
                                          {0, 0.0823, 0}}};

Eigen::Isometry3d dh_flange(const std::array<double, kJoints>& q) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  for (int i = 0; i < kJoints; ++i) {
    t = t * Eigen::AngleAxisd(q[i], Eigen::Vector3d::UnitZ()) * Eigen::Translation3d(kDh[i].a, 0, kDh[i].d) *
        Eigen::AngleAxisd(kDh[i].alpha, Eigen::Vector3d::UnitX());
  }
  return t;
}

class Ur5Arm : public ::testing::Test {
 protected:
  void expect_flange_at(const std::array<double, kJoints>& q) {
    sim_.reset();
    for (int i = 0; i < kJoints; ++i) sim_.data()->qpos[sim_.joint_qpos_address(kNames[i])] = q[i];
    mj_kinematics(sim_.model(), sim_.data());
    // the arm's base frame: body ur5_base in the world
    Eigen::Isometry3d world_base = Eigen::Isometry3d::Identity();
    const int b = sim_.body_id("ur5_base");
    world_base.translation() = test::vec3(sim_.data()->xpos + 3 * b);
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) world_base.linear()(r, c) = sim_.data()->xmat[9 * b + 3 * r + c];
    }
    const Eigen::Isometry3d expected = world_base * dh_flange(q);
    const Eigen::Isometry3d actual = test::site_pose(sim_.data(), sim_.site_id("flange_site"));
    EXPECT_LT((actual.translation() - expected.translation()).norm(), 1e-9);
    EXPECT_LT((actual.linear() - expected.linear()).norm(), 1e-9);
  }
  MujocoModel sim_ = MujocoModel::load(test::model_path("scene_ur5_svh.xml"));
};

TEST_F(Ur5Arm, PutsTheFlangeOnTheDhFlangeAtZeroAtTablesPosesAndAtRandomPoses) {
  expect_flange_at({0, 0, 0, 0, 0, 0});
  expect_flange_at({1.5707, -1.5447, 1.5447, -1.5794, -1.5794, 0});  // Table I "home"
  expect_flange_at({1.5707, 0.4014, 0.9250, 2.3387, 1.5794, 0});     // Table I "test"
  std::mt19937 rng(20);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI);
  for (int n = 0; n < 50; ++n) {
    std::array<double, kJoints> q{};
    for (double& v : q) v = angle(rng);
    expect_flange_at(q);
  }
}

TEST_F(Ur5Arm, HasUrMassesRangesAndTorqueLimits) {
  const mjModel* m = sim_.model();
  const std::array<double, kJoints> mass = {3.7, 8.393, 2.275, 1.219, 1.219, 0.1879};
  const std::array<double, kJoints> torque = {150, 150, 150, 28, 28, 28};
  for (int i = 0; i < kJoints; ++i) {
    const int j = sim_.joint_id(kNames[i]);
    EXPECT_DOUBLE_EQ(m->body_mass[m->jnt_bodyid[j]], mass[i]) << kNames[i];
    const double range = i == 2 ? M_PI : 2 * M_PI;
    EXPECT_NEAR(m->jnt_range[2 * j], -range, 1e-6) << kNames[i];
    EXPECT_NEAR(m->jnt_range[2 * j + 1], range, 1e-6) << kNames[i];
    const int a = sim_.actuator_id(kNames[i]);
    EXPECT_EQ(m->actuator_trnid[2 * a], j);
    EXPECT_DOUBLE_EQ(m->actuator_ctrlrange[2 * a + 1], torque[i]) << kNames[i];
  }
  // the scene's own contact solver (docs/hand.md), on top of the project's 1 kHz Euler
  EXPECT_EQ(m->opt.cone, mjCONE_ELLIPTIC);
  EXPECT_EQ(m->opt.noslip_iterations, 10);
  EXPECT_EQ(m->opt.integrator, mjINT_EULER);
  EXPECT_DOUBLE_EQ(m->opt.timestep, 0.001);
}

}  // namespace
}  // namespace teleop::sim
