#include "teleop/view/posed_scene.h"

#include <gtest/gtest.h>

#include <array>

#include "teleop/view/view_model.h"

namespace teleop::view {
namespace {

ViewModelSpec spec(const std::string& node) {
  return read_view_model(std::string(TELEOP_SOURCE_DIR) + "/config/nodes/" + node);
}

TEST(PosedScene, ALayerIsShownOnlyOncePosedAndOnlyWithTheArmsJointCount) {
  PosedScene scene(spec("follower.yaml"));
  ASSERT_EQ(scene.arm_count(), 1u);
  ASSERT_EQ(scene.joint_count(0), 7u);
  EXPECT_FALSE(scene.posed(Layer::kFollower));
  EXPECT_FALSE(scene.posed(Layer::kTwin));
  const std::array<double, 6> six{};
  EXPECT_FALSE(scene.set_joints(Layer::kFollower, 0, six.data(), six.size()));
  EXPECT_FALSE(scene.posed(Layer::kFollower));

  const std::array<double, 7> q{0.3, -0.2, 0.1, -2.0, 0.0, 3.0, 0.7};
  const std::array<double, 7> tau{1, 2, 3, 4, 5, 6, 7};
  ASSERT_TRUE(scene.set_joints(Layer::kFollower, 0, q.data(), q.size(), nullptr, tau.data()));
  EXPECT_TRUE(scene.posed(Layer::kFollower));
  EXPECT_FALSE(scene.posed(Layer::kTwin));
  const mjData* d = scene.data(Layer::kFollower);
  for (size_t i = 0; i < 7; ++i) {
    EXPECT_DOUBLE_EQ(d->qpos[i], q[i]);
    EXPECT_DOUBLE_EQ(d->qfrc_applied[i], tau[i]);
  }
  // the twin's data is its own
  EXPECT_NE(scene.data(Layer::kTwin)->qpos[0], q[0]);
  scene.update();
  scene.clear(Layer::kFollower);
  EXPECT_FALSE(scene.posed(Layer::kFollower));
}

TEST(PosedScene, TheHandsJointsArePosedByNameCoupledOnesToo) {
  PosedScene scene(spec("hand_mujoco.yaml"));
  const mjModel* m = scene.model();
  ASSERT_EQ(scene.arm_count(), 1u);
  ASSERT_EQ(scene.joint_count(0), 20u);
  std::array<double, 20> q{};
  for (size_t i = 0; i < q.size(); ++i) q[i] = 0.01 * static_cast<double>(i + 1);
  ASSERT_TRUE(scene.set_joints(Layer::kFollower, 0, q.data(), q.size()));
  const mjData* d = scene.data(Layer::kFollower);
  // j3 (index 1) is a coupled joint without an actuator; index_spread (18) is coupled to the
  // finger spread
  const int j3 = mj_name2id(m, mjOBJ_JOINT, "j3");
  const int spread = mj_name2id(m, mjOBJ_JOINT, "index_spread");
  const int j17 = mj_name2id(m, mjOBJ_JOINT, "j17");
  const int base = mj_name2id(m, mjOBJ_BODY, "svh_base_link");
  ASSERT_GE(j3, 0);
  ASSERT_GE(spread, 0);
  ASSERT_GE(j17, 0);
  ASSERT_GE(base, 0);
  EXPECT_DOUBLE_EQ(d->qpos[m->jnt_qposadr[j3]], q[1]);
  EXPECT_DOUBLE_EQ(d->qpos[m->jnt_qposadr[spread]], q[18]);
  EXPECT_TRUE(scene.moved_by_arms(m->jnt_bodyid[j17]));
  EXPECT_FALSE(scene.moved_by_arms(base));
  // the object is the emulator's, not one the follower tracks: posing the hand leaves it where
  // the model starts it
  ASSERT_EQ(scene.free_bodies().size(), 1u);
  scene.update();
  const FreeBody& object = scene.free_bodies()[0];
  for (int i = 0; i < 7; ++i) EXPECT_DOUBLE_EQ(d->qpos[object.qpos + i], m->qpos0[object.qpos + i]) << i;
}

TEST(PosedScene, GhostsAreTheBodiesTheArmsMove) {
  PosedScene scene(spec("follower.yaml"));
  const mjModel* m = scene.model();
  EXPECT_FALSE(scene.moved_by_arms(0));  // the world, with the wall
  EXPECT_TRUE(scene.moved_by_arms(mj_name2id(m, mjOBJ_BODY, "link7")));
  EXPECT_TRUE(scene.moved_by_arms(mj_name2id(m, mjOBJ_BODY, "link1")));
  EXPECT_TRUE(scene.free_bodies().empty());
  EXPECT_EQ(scene.ee_site(0), mj_name2id(m, mjOBJ_SITE, "ee_site"));
  EXPECT_GE(scene.ee_site(0), 0);
}

TEST(PosedScene, TheBoxTaskHasTwoArmsAndAFreeBox) {
  PosedScene scene(spec("follower_box_task.yaml"));
  const mjModel* m = scene.model();
  ASSERT_EQ(scene.arm_count(), 2u);
  EXPECT_EQ(scene.joint_count(0), 7u);
  EXPECT_EQ(scene.joint_count(1), 7u);
  ASSERT_EQ(scene.free_bodies().size(), 1u);
  EXPECT_EQ(scene.free_bodies()[0].name, "box");
  EXPECT_FALSE(scene.moved_by_arms(scene.free_bodies()[0].body));
  EXPECT_TRUE(scene.moved_by_arms(mj_name2id(m, mjOBJ_BODY, "left_link7")));
  EXPECT_TRUE(scene.moved_by_arms(mj_name2id(m, mjOBJ_BODY, "right_link7")));
  EXPECT_EQ(scene.ee_site(1), mj_name2id(m, mjOBJ_SITE, "right_ee_site"));
  // the twin's config names no sites: <prefix>ee_site
  PosedScene twin(spec("twin_box_task.yaml"));
  EXPECT_EQ(twin.ee_site(0), mj_name2id(twin.model(), mjOBJ_SITE, "left_ee_site"));

  // the right arm's joints are its own
  const std::array<double, 7> q{0.5, 0.5, 0.5, -2.0, 0.5, 2.5, 0.5};
  ASSERT_TRUE(scene.set_joints(Layer::kTwin, 1, q.data(), q.size()));
  const mjData* d = scene.data(Layer::kTwin);
  EXPECT_DOUBLE_EQ(d->qpos[m->jnt_qposadr[mj_name2id(m, mjOBJ_JOINT, "right_joint1")]], 0.5);
  EXPECT_DOUBLE_EQ(d->qpos[m->jnt_qposadr[mj_name2id(m, mjOBJ_JOINT, "left_joint1")]], -0.066);

  const double position[3] = {0.6, 0.0, 0.9};
  const double quaternion[4] = {2, 0, 0, 0};
  scene.set_body_pose(Layer::kFollower, 0, position, quaternion);
  const int adr = scene.free_bodies()[0].qpos;
  EXPECT_DOUBLE_EQ(scene.data(Layer::kFollower)->qpos[adr], 0.6);
  EXPECT_DOUBLE_EQ(scene.data(Layer::kFollower)->qpos[adr + 3], 1.0);  // normalised
}

}  // namespace
}  // namespace teleop::view
