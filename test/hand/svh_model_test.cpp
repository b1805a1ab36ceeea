// The SVH-class hand's MuJoCo models (config/models/svh_hand.xml, scene_ur5_svh.xml) against the
// coupling table of hand_coupling.cpp, the one source of truth for the couplings.
#include "teleop/hand/svh_model.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "teleop/sim/mujoco_model.h"

namespace teleop::hand {
namespace {

std::string model_path(const std::string& name) { return std::string(TELEOP_SOURCE_DIR) + "/config/models/" + name; }

size_t joint(std::string_view name) {
  for (size_t j = 0; j < kHandJoints; ++j) {
    if (kHandJointNames[j] == name) return j;
  }
  ADD_FAILURE() << "no joint " << name;
  return 0;
}

class SvhModels : public ::testing::TestWithParam<const char*> {};

TEST_P(SvhModels, EveryEqualityIsTheCouplingTablesFactorAndOffset) {
  const sim::MujocoModel sim = sim::MujocoModel::load(model_path(GetParam()));
  const mjModel* m = sim.model();
  const HandCoupling table = HandCoupling::svh();
  int coupled = 0;
  for (size_t j = 0; j < kHandJoints; ++j) {
    const CouplingTerm& term = table.terms()[j];
    const size_t main = joint(kHandMotorNames[term.motor]);
    if (j == main) continue;
    ++coupled;
    // the equality on this joint, read from the compiled model, not through the code under test
    const int id = sim.joint_id(kHandJointNames[j]);
    int e = -1;
    for (int i = 0; i < m->neq; ++i) {
      if (m->eq_type[i] == mjEQ_JOINT && m->eq_obj1id[i] == id) e = i;
    }
    ASSERT_GE(e, 0) << kHandJointNames[j];
    EXPECT_EQ(m->eq_obj2id[e], sim.joint_id(kHandJointNames[main])) << kHandJointNames[j];
    const mjtNum* c = m->eq_data + e * mjNEQDATA;
    const double factor = term.factor / table.terms()[main].factor;
    EXPECT_EQ(c[0], table.offsets()[j] - factor * table.offsets()[main]) << kHandJointNames[j];
    EXPECT_EQ(c[1], factor) << kHandJointNames[j];
    EXPECT_EQ(c[2], 0.0);
    EXPECT_EQ(c[3], 0.0);
    EXPECT_EQ(c[4], 0.0);
    EXPECT_TRUE(m->eq_active[e]);
  }
  EXPECT_EQ(coupled, 11);
  EXPECT_EQ(m->neq, 11);
}

TEST_P(SvhModels, IndexFindsTwentyJointsNineMotorsAndTheTipSensor) {
  const sim::MujocoModel sim = sim::MujocoModel::load(model_path(GetParam()));
  EXPECT_EQ(sim.load_warning(), "");
  const SvhModelIndex index = index_svh_model(sim.model(), sim.path(), HandCoupling::svh());
  for (size_t k = 0; k < kHandMotors; ++k) {
    EXPECT_EQ(index.actuator[k], sim.actuator_id(kHandMotorNames[k]));
    EXPECT_EQ(index.equality[main_joint_of(k)], -1);
    EXPECT_EQ(index.main_joint[k], main_joint_of(k));
    EXPECT_EQ(kHandJointNames[index.main_joint[k]], kHandMotorNames[k]);
  }
  int coupled = 0;
  for (size_t j = 0; j < kHandJoints; ++j) coupled += index.equality[j] >= 0;
  EXPECT_EQ(coupled, 11);
  EXPECT_GE(index.tip_touch_address, 0);
  // the hand weighs the SVH's 1.3 kg (paper §II-C)
  EXPECT_NEAR(sim.model()->body_subtreemass[sim.body_id("svh_mount")], 1.3, 1e-9);
}

INSTANTIATE_TEST_SUITE_P(HandAloneAndScene, SvhModels, ::testing::Values("svh_hand.xml", "scene_ur5_svh.xml"));

TEST(SvhModel, RefusesAModelWhoseEqualityDiffersFromTheTable) {
  const sim::MujocoModel sim = sim::MujocoModel::load(model_path("svh_hand.xml"));
  // the table with j16's factor changed: the model no longer agrees, and the error names j16
  std::array<CouplingTerm, kHandJoints> terms = HandCoupling::svh().terms();
  terms[joint("j16")].factor = 1.43;
  const HandCoupling changed(terms, HandJointVector{});
  try {
    index_svh_model(sim.model(), sim.path(), changed);
    FAIL() << "accepted a model that disagrees with the table";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("'j16'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("hand_coupling.cpp"), std::string::npos) << e.what();
  }
  // an offset the model lacks is refused too
  HandJointVector offsets{};
  offsets[joint("j4")] = 0.1;
  EXPECT_THROW(index_svh_model(sim.model(), sim.path(), HandCoupling(HandCoupling::svh().terms(), offsets)),
               std::runtime_error);
}

TEST(SvhModel, RefusesAModelWithoutTheHand) {
  const sim::MujocoModel sim = sim::MujocoModel::load(model_path("panda.xml"));
  EXPECT_THROW(index_svh_model(sim.model(), sim.path(), HandCoupling::svh()), std::runtime_error);
}

TEST(SvhModel, MotorRangeIsWhatEveryJointOfTheMotorAllows) {
  const sim::MujocoModel sim = sim::MujocoModel::load(model_path("svh_hand.xml"));
  const SvhModelIndex index = index_svh_model(sim.model(), sim.path(), HandCoupling::svh());
  // middle distal: the URDF lets the motor's joint reach 1.334 rad but j15 = 1.0454 x it only 1.334
  EXPECT_NEAR(index.motor_max_rad[hand_motor::kMiddleDistal], 1.334 / 1.0454, 1e-12);
  // spread: index and ring spread (0.5 x) stop at 0.28833 before Finger_Spread's own 0.5829
  EXPECT_NEAR(index.motor_max_rad[hand_motor::kFingerSpread], 0.28833 / 0.5, 1e-12);
  // index distal: j14 (1.394 / 1.045 = 1.33397) stops it just before its own 1.334
  EXPECT_NEAR(index.motor_max_rad[hand_motor::kIndexDistal], 1.394 / 1.045, 1e-12);
  for (size_t k = 0; k < kHandMotors; ++k) EXPECT_EQ(index.motor_min_rad[k], 0.0) << kHandMotorNames[k];
}

TEST(SvhScene, KeyframesHoldTheCouplingAndOnlyTheIndexTipTouchesThePanelAtTest) {
  sim::MujocoModel sim = sim::MujocoModel::load(model_path("scene_ur5_svh.xml"));
  const SvhModelIndex index = index_svh_model(sim.model(), sim.path(), HandCoupling::svh());
  const HandCoupling table = HandCoupling::svh();
  for (const char* key : {"home", "test"}) {
    sim.reset(key);
    for (size_t j = 0; j < kHandJoints; ++j) {
      const CouplingPolynomial p = coupling_polynomial(table, j);
      EXPECT_NEAR(sim.data()->qpos[index.qpos[j]], p.c0_rad + p.c1 * sim.data()->qpos[index.qpos[p.main_joint]], 1e-8)
          << key << " " << kHandJointNames[j];
    }
  }
  sim.reset("home");
  EXPECT_EQ(sim.data()->ncon, 0);
  sim.reset("test");
  ASSERT_EQ(sim.data()->ncon, 1);
  const mjContact& c = sim.data()->contact[0];
  const int tip = sim.geom_id("svh_index_distal");
  const int panel = sim.geom_id("panel");
  EXPECT_TRUE((c.geom1 == tip && c.geom2 == panel) || (c.geom1 == panel && c.geom2 == tip));
  // the panel's face is 2 mm short of the free fingertip: the controllers press it 2 mm in
  EXPECT_NEAR(c.dist, -0.002, 1e-4);
}

}  // namespace
}  // namespace teleop::hand
