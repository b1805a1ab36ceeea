#include "teleop/view/view_model.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "teleop/common/config.h"

namespace teleop::view {
namespace {

std::string config(const std::string& name) { return std::string(TELEOP_SOURCE_DIR) + "/config/nodes/" + name; }
std::string filename(const std::string& path) { return std::filesystem::path(path).filename().string(); }

TEST(ViewModel, TheFollowerShowsItsSimulatedWorld) {
  const ViewModelSpec s = read_view_model(config("follower.yaml"));
  EXPECT_EQ(filename(s.model_path), "scene_wall.xml");
  EXPECT_TRUE(std::filesystem::exists(s.model_path));
  EXPECT_EQ(s.keyframe, "facing_wall");
  ASSERT_EQ(s.arms.size(), 1u);
  EXPECT_EQ(s.arms[0].name, "");
  EXPECT_EQ(s.arms[0].joint_prefix, "");
  EXPECT_EQ(s.arms[0].ee_site, "ee_site");
}

TEST(ViewModel, TheBoxTasksFollowerHasTwoArmsOnTheirPrefixes) {
  const ViewModelSpec s = read_view_model(config("follower_box_task.yaml"));
  EXPECT_EQ(filename(s.model_path), "scene_box_shelf.xml");
  EXPECT_EQ(s.keyframe, "home");
  ASSERT_EQ(s.arms.size(), 2u);
  EXPECT_EQ(s.arms[0].name, "left");
  EXPECT_EQ(s.arms[0].joint_prefix, "left_");
  EXPECT_EQ(s.arms[1].name, "right");
  EXPECT_EQ(s.arms[1].joint_prefix, "right_");
  EXPECT_EQ(s.arms[0].ee_site, "left_ee_site");
  EXPECT_EQ(s.arms[1].ee_site, "right_ee_site");
}

TEST(ViewModel, TheTwinShowsItsOwnModel) {
  const ViewModelSpec s = read_view_model(config("twin.yaml"));
  EXPECT_EQ(filename(s.model_path), "scene_wall.xml");
  EXPECT_EQ(s.keyframe, "facing_wall");
  EXPECT_EQ(read_view_model(config("twin_box_task.yaml")).arms.size(), 2u);
}

TEST(ViewModel, TheHandShowsTheEmulatorsHandPosedByItsJointStateByName) {
  const ViewModelSpec s = read_view_model(config("hand_mujoco.yaml"));
  EXPECT_EQ(filename(s.model_path), "svh_hand_grasp.xml");
  EXPECT_TRUE(std::filesystem::exists(s.model_path));
  ASSERT_EQ(s.arms.size(), 1u);
  EXPECT_EQ(s.arms[0].state_topic, "teleop/hand/joint_state");
  ASSERT_EQ(s.arms[0].joint_names.size(), 20u);
  EXPECT_EQ(s.arms[0].joint_names.front(), "Thumb_Flexion");
  // the hand on the real bus (hand.yaml) is shown the same way
  EXPECT_EQ(read_view_model(config("hand.yaml")).arms[0].joint_names, s.arms[0].joint_names);
}

TEST(ViewModel, AConfigWithoutAFollowerOrTwinIsRefusedNamingTheFile) {
  try {
    read_view_model(config("leader.yaml"));
    FAIL() << "expected a ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("leader.yaml"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("no follower, twin or hand section"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace teleop::view
