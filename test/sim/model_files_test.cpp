// Every model and scene in config/models/ with MuJoCo 2.2.2, and what each scene is for.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "sim_test_util.h"
#include "teleop/sim/mujoco_model.h"

namespace teleop::sim {
namespace {

using test::model_path;

// the top-level models: every *.xml directly in config/models/ (parts/, generated/ and templates/
// hold include fragments)
std::vector<std::string> top_level_models() {
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(model_path(""))) {
    if (entry.is_regular_file() && entry.path().extension() == ".xml") files.push_back(entry.path().string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

bool collides(const mjModel* m, int g1, int g2) {
  return (m->geom_contype[g1] & m->geom_conaffinity[g2]) != 0 || (m->geom_contype[g2] & m->geom_conaffinity[g1]) != 0;
}

bool is_arm_geom(const mjModel* m, int g) { return (m->geom_contype[g] & (2 | 4)) != 0; }

TEST(ModelFiles, LoadsEveryModelAndSceneWhenCompiledByMujoco) {
  EXPECT_EQ(mj_version(), 222) << "these models are written for MuJoCo 2.2.2";
  const auto files = top_level_models();
  const std::vector<std::string> expected{"dual_arm.xml",       "dual_arm_mobile.xml", "left_arm.xml",
                                          "right_arm.xml",      "panda.xml",           "scene_box_shelf.xml",
                                          "scene_table.xml",    "scene_wall.xml",      "scene_wiping.xml",
                                          "svh_hand.xml",       "scene_ur5_svh.xml",   "svh_hand_grasp.xml"};
  for (const auto& name : expected) {
    EXPECT_NE(std::find(files.begin(), files.end(), model_path(name)), files.end()) << name;
  }
  for (const auto& file : files) {
    SCOPED_TRACE(file);
    MujocoModel sim = MujocoModel::load(file);  // throws with MuJoCo's error on failure
    EXPECT_EQ(sim.load_warning(), "");
    EXPECT_DOUBLE_EQ(sim.model()->opt.timestep, 0.001);
    EXPECT_GE(sim.model()->nu, 7);
    for (int i = 0; i < 100; ++i) mj_step(sim.model(), sim.data());
    for (int w = 0; w < mjNWARNING; ++w) EXPECT_EQ(sim.data()->warning[w].number, 0) << "warning " << w;
  }
}

// a keyframe made to touch: the SVH study's "test" pose presses the index tip on the panel
// (test/hand/svh_model_test.cpp checks that it is the only contact, 2 mm deep)
bool intended_contact(const std::string& file, const mjModel* m, int key, const mjContact& con) {
  const std::string g1 = mj_id2name(m, mjOBJ_GEOM, con.geom1);
  const std::string g2 = mj_id2name(m, mjOBJ_GEOM, con.geom2);
  return file == model_path("scene_ur5_svh.xml") && std::string(mj_id2name(m, mjOBJ_KEY, key)) == "test" &&
         ((g1 == "svh_index_distal" && g2 == "panel") || (g1 == "panel" && g2 == "svh_index_distal"));
}

TEST(ModelFiles, StartsEveryKeyframeInsideTheJointRangesAndFreeOfArmContactsWhenReset) {
  for (const auto& file : top_level_models()) {
    MujocoModel sim = MujocoModel::load(file);
    const mjModel* m = sim.model();
    for (int k = 0; k < m->nkey; ++k) {
      SCOPED_TRACE(file + " key " + mj_id2name(m, mjOBJ_KEY, k));
      sim.reset(mj_id2name(m, mjOBJ_KEY, k));
      for (int j = 0; j < m->njnt; ++j) {
        if (!m->jnt_limited[j]) continue;
        const double q = sim.data()->qpos[m->jnt_qposadr[j]];
        EXPECT_GE(q, m->jnt_range[2 * j]) << mj_id2name(m, mjOBJ_JOINT, j);
        EXPECT_LE(q, m->jnt_range[2 * j + 1]) << mj_id2name(m, mjOBJ_JOINT, j);
      }
      for (int c = 0; c < sim.data()->ncon; ++c) {
        const mjContact& con = sim.data()->contact[c];
        if (intended_contact(file, m, k, con)) continue;
        EXPECT_FALSE(is_arm_geom(m, con.geom1) || is_arm_geom(m, con.geom2))
            << mj_id2name(m, mjOBJ_GEOM, con.geom1) << " touches " << mj_id2name(m, mjOBJ_GEOM, con.geom2);
      }
    }
  }
}

TEST(DualArm, HasFourteenArmJointsAndBothEeSitesWhenLoaded) {
  for (const std::string name : {"dual_arm.xml", "dual_arm_mobile.xml"}) {
    SCOPED_TRACE(name);
    const MujocoModel sim = MujocoModel::load(model_path(name));
    const mjModel* m = sim.model();
    const int base_dofs = name == "dual_arm.xml" ? 0 : 3;
    EXPECT_EQ(m->nv, 14 + base_dofs);
    EXPECT_EQ(m->nu, 14 + base_dofs);
    for (const std::string side : {"left_", "right_"}) {
      for (int i = 1; i <= 7; ++i) {
        const int j = sim.joint_id(side + "joint" + std::to_string(i));
        EXPECT_EQ(m->jnt_type[j], mjJNT_HINGE);
        const int a = sim.actuator_id(side + "motor" + std::to_string(i));
        EXPECT_EQ(m->actuator_trnid[2 * a], j);
        EXPECT_DOUBLE_EQ(m->actuator_ctrlrange[2 * a + 1], i <= 4 ? 87.0 : 12.0);
      }
      EXPECT_NO_THROW((void)sim.site_id(side + "ee_site"));
    }
    if (base_dofs > 0) {
      EXPECT_EQ(m->jnt_type[sim.joint_id("base_x")], mjJNT_SLIDE);
      EXPECT_EQ(m->jnt_type[sim.joint_id("base_y")], mjJNT_SLIDE);
      EXPECT_EQ(m->jnt_type[sim.joint_id("base_yaw")], mjJNT_HINGE);
    }
  }
}

TEST(DualArm, LetsArmsTouchEachOtherAndTheTorsoButNotThemselvesWhenColliding) {
  const MujocoModel sim = MujocoModel::load(model_path("dual_arm.xml"));
  const mjModel* m = sim.model();
  const int left = sim.geom_id("left_link7_flange");
  const int right = sim.geom_id("right_link7_flange");
  EXPECT_TRUE(collides(m, left, right));
  EXPECT_TRUE(collides(m, left, sim.geom_id("torso_column")));
  EXPECT_TRUE(collides(m, right, sim.geom_id("head")));
  EXPECT_TRUE(collides(m, left, sim.geom_id("floor")));
  EXPECT_FALSE(collides(m, left, sim.geom_id("left_link5_forearm")));
  EXPECT_FALSE(collides(m, right, sim.geom_id("right_link2_upper")));
  EXPECT_FALSE(collides(m, sim.geom_id("left_link0_column"), sim.geom_id("torso_column")));
}

TEST(DualArm, MirrorsTheRightHandOntoTheLeftWhenAtHome) {
  // the right arm is the mirror image of the left: mirrored joint angles give mirrored flanges
  MujocoModel sim = MujocoModel::load(model_path("dual_arm.xml"));
  sim.reset("home");
  const Eigen::Vector3d left = test::vec3(sim.data()->site_xpos + 3 * sim.site_id("left_ee_site"));
  const Eigen::Vector3d right = test::vec3(sim.data()->site_xpos + 3 * sim.site_id("right_ee_site"));
  EXPECT_NEAR(left.x(), right.x(), 1e-9);
  EXPECT_NEAR(left.y(), -right.y(), 1e-9);
  EXPECT_NEAR(left.z(), right.z(), 1e-9);
  EXPECT_NEAR(left.y() - right.y(), 0.4, 0.01);  // hands 0.4 m apart in "home"
}

TEST(SingleArmModels, PutTheFlangeWhereTheTwoArmBodyHasItWhenAtHome) {
  // left_arm.xml / right_arm.xml model one arm of the robot on its own (controller model, haptic
  // device): same mount, so the same flange pose for the same joints
  MujocoModel body = MujocoModel::load(model_path("dual_arm.xml"));
  body.reset("home");
  for (const std::string side : {"left", "right"}) {
    SCOPED_TRACE(side);
    MujocoModel arm = MujocoModel::load(model_path(side + "_arm.xml"));
    arm.reset("home");
    ASSERT_EQ(arm.model()->nv, 7);
    const int offset = side == "left" ? 0 : 7;
    for (int j = 0; j < 7; ++j) EXPECT_DOUBLE_EQ(arm.data()->qpos[j], body.data()->qpos[offset + j]);
    const std::string site = side + "_ee_site";
    const Eigen::Vector3d in_body = test::vec3(body.data()->site_xpos + 3 * body.site_id(site));
    const Eigen::Vector3d alone = test::vec3(arm.data()->site_xpos + 3 * arm.site_id(site));
    EXPECT_LT((in_body - alone).norm(), 1e-9);
    for (int k = 0; k < 9; ++k) {
      EXPECT_NEAR(arm.data()->site_xmat[9 * arm.site_id(site) + k],
                  body.data()->site_xmat[9 * body.site_id(site) + k], 1e-9);
    }
  }
}

TEST(SceneWall, ProducesConstraintForceWhenEeIsDrivenIntoTheWall) {
  MujocoModel sim = MujocoModel::load(model_path("scene_wall.xml"));
  sim.model()->opt.disableflags |= mjDSBL_FRICTIONLOSS;  // so that contact is all qfrc_constraint holds
  sim.reset("facing_wall");
  const mjModel* m = sim.model();
  const mjData* d = sim.data();
  const int site = sim.site_id("ee_site");
  const int wall = sim.geom_id("wall");
  const double wall_x = m->geom_pos[3 * wall] - m->geom_size[3 * wall];
  const Eigen::Vector3d push(20.0, 0.0, 0.0);  // N, towards the wall

  test::drive_site(sim, site, Eigen::Vector3d::Zero(), 2.0, 0.1);
  EXPECT_EQ(d->ncon, 0);
  EXPECT_LT(Eigen::Map<const Eigen::VectorXd>(d->qfrc_constraint, m->nv).norm(), 1e-9);

  double deepest = 0;
  test::drive_site(sim, site, push, 2.0, 2.0, [&] { deepest = std::max(deepest, d->site_xpos[3 * site] - wall_x); });
  EXPECT_TRUE(test::subtree_in_contact_with(m, d, sim.body_id("link7"), wall));
  const Eigen::VectorXd constraint = Eigen::Map<const Eigen::VectorXd>(d->qfrc_constraint, m->nv);
  EXPECT_GT(constraint.norm(), 1.0);
  // at rest against the wall, the wall's generalised force balances J^T F
  std::vector<mjtNum> jacp(3 * static_cast<size_t>(m->nv));
  mj_jacSite(m, d, jacp.data(), nullptr, site);
  const Eigen::Map<const Eigen::Matrix<mjtNum, 3, Eigen::Dynamic, Eigen::RowMajor>> jacobian(jacp.data(), 3, m->nv);
  const Eigen::VectorXd applied = jacobian.transpose() * push;
  EXPECT_LT((constraint + applied).norm(), 0.1 * applied.norm()) << constraint.transpose() << "\n"
                                                                 << applied.transpose();
  // the flange stays put (the wrist may still roll slowly about the capsule's tip)
  EXPECT_LT((jacobian * Eigen::Map<const Eigen::VectorXd>(d->qvel, m->nv)).norm(), 1e-3);
  EXPECT_LT(deepest, 0.002) << "a stiff wall: at most 2 mm of penetration under 20 N";
}

TEST(SceneTable, PutsThePlaneTwoCentimetresBelowTheBaseAndStopsTheEeWhenPushedDown) {
  MujocoModel sim = MujocoModel::load(model_path("scene_table.xml"));
  sim.reset("above_table");
  const mjModel* m = sim.model();
  const int table = sim.geom_id("table");
  EXPECT_EQ(m->geom_type[table], mjGEOM_PLANE);
  EXPECT_NEAR(m->geom_pos[3 * table + 2], -0.02, 1e-12);  // PARTI §3.2
  test::drive_site(sim, sim.site_id("ee_site"), {0.0, 0.0, -15.0}, 3.0, 1.5);
  EXPECT_TRUE(test::subtree_in_contact_with(m, sim.data(), sim.body_id("link7"), table));
  EXPECT_NEAR(sim.data()->site_xpos[2], -0.02, 0.003);  // the flange rests on the plane
}

TEST(SceneBoxShelf, HasThePartiClearancesWhenLoaded) {
  const MujocoModel sim = MujocoModel::load(model_path("scene_box_shelf.xml"));
  const mjModel* m = sim.model();
  auto pos = [&](const char* g, int k) { return m->geom_pos[3 * sim.geom_id(g) + k]; };
  auto size = [&](const char* g, int k) { return m->geom_size[3 * sim.geom_id(g) + k]; };
  const double box = 2 * size("box", 0);
  ASSERT_DOUBLE_EQ(size("box", 0), size("box", 1));
  const double socket_x =
      (pos("socket_front", 0) - size("socket_front", 0)) - (pos("socket_back", 0) + size("socket_back", 0));
  const double socket_y =
      (pos("socket_left", 1) - size("socket_left", 1)) - (pos("socket_right", 1) + size("socket_right", 1));
  EXPECT_NEAR(socket_x - box, 0.002, 1e-9);  // PARTI §3.3: 2 mm
  EXPECT_NEAR(socket_y - box, 0.002, 1e-9);
  const double opening =
      (pos("shelf_ceiling", 2) - size("shelf_ceiling", 2)) - (pos("shelf_floor", 2) + size("shelf_floor", 2));
  EXPECT_NEAR(opening - 2 * size("box", 2), 0.02, 1e-9);  // PARTI §3.3: 2 cm
}

TEST(SceneBoxShelf, KeepsTheBoxInItsSocketWhenTheRobotHoldsHome) {
  MujocoModel sim = MujocoModel::load(model_path("scene_box_shelf.xml"));
  sim.reset("home");
  const int box = sim.body_id("box");
  const Eigen::Vector3d start = test::vec3(sim.data()->xpos + 3 * box);
  test::drive_site(sim, -1, Eigen::Vector3d::Zero(), 2.0, 2.0);
  EXPECT_LT((test::vec3(sim.data()->xpos + 3 * box) - start).norm(), 1e-3);
  EXPECT_LT(std::abs(sim.data()->qvel[sim.joint_dof_address("base_x")]), 1e-3);
}

TEST(SceneWiping, PressesTheWiperOnThePanelWhenPushedTowardsIt) {
  MujocoModel sim = MujocoModel::load(model_path("scene_wiping.xml"));
  sim.reset("ready");
  const int panel = sim.geom_id("panel");
  const int head = sim.geom_id("wiper_head");
  // the panel's normal (its geom z axis), pointing up and towards the robot
  const mjtNum* axes = sim.data()->geom_xmat + 9 * panel;
  const Eigen::Vector3d normal(axes[2], axes[5], axes[8]);
  EXPECT_LT(normal.x(), -0.3);
  EXPECT_GT(normal.z(), 0.9);
  test::drive_site(sim, sim.site_id("tool_site"), -15.0 * normal, 3.0, 3.0);
  EXPECT_TRUE(test::in_contact(sim.data(), head, panel));
}

}  // namespace
}  // namespace teleop::sim
