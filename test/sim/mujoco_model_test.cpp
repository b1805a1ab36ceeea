#include "teleop/sim/mujoco_model.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <stdexcept>
#include <string>
#include <utility>

#include "sim_test_util.h"
#include "test_helpers.h"

namespace teleop::sim {
namespace {

using test::model_path;

using teleop::test::error_of;
using teleop::test::TempDir;

TEST(MujocoModel, OwnsModelAndDataWhenFileLoads) {
  MujocoModel sim = MujocoModel::load(model_path("panda.xml"));
  ASSERT_NE(sim.model(), nullptr);
  ASSERT_NE(sim.data(), nullptr);
  EXPECT_EQ(sim.model()->nq, 7);
  EXPECT_EQ(sim.path(), model_path("panda.xml"));
  EXPECT_EQ(sim.load_warning(), "");
  // derived quantities are ready after loading: the flange of the zero pose (DH table)
  EXPECT_NEAR(sim.data()->site_xpos[2], 0.333 + 0.316 + 0.384 - 0.107, 1e-12);
}

TEST(MujocoModel, ThrowsNamingTheFileWhenFileIsMissing) {
  TempDir dir("teleop_sim_test");
  const std::string path = dir.path("no_such_model.xml");
  const std::string message = error_of<std::runtime_error>([&] { MujocoModel::load(path); });
  EXPECT_NE(message.find(path), std::string::npos) << message;
  EXPECT_NE(message.find("FILE_NOT_FOUND"), std::string::npos) << message;  // MuJoCo's own text
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

TEST(MujocoModel, ThrowsNamingTheFileAndMujocosErrorWhenXmlIsMalformed) {
  TempDir dir("teleop_sim_test");
  const std::string path = dir.write("broken.xml", "<mujoco>\n  <worldbody>\n    <body>\n</mujoco>\n");
  const std::string message = error_of<std::runtime_error>([&] { MujocoModel::load(path); });
  EXPECT_NE(message.find(path), std::string::npos) << message;
  EXPECT_NE(message.find("XML_ERROR_MISMATCHED_ELEMENT"), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

TEST(MujocoModel, ThrowsNamingTheFileAndMujocosErrorWhenModelDoesNotCompile) {
  TempDir dir("teleop_sim_test");
  const std::string path = dir.write("bad_actuator.xml",
                                     "<mujoco><worldbody><body><joint name='j'/><geom size='0.1'/></body></worldbody>"
                                     "<actuator><motor joint='no_such_joint'/></actuator></mujoco>");
  const std::string message = error_of<std::runtime_error>([&] { MujocoModel::load(path); });
  EXPECT_NE(message.find(path), std::string::npos) << message;
  EXPECT_NE(message.find("no_such_joint"), std::string::npos) << message;
}

TEST(MujocoModel, ThrowsNamingTheFileWhenAnIncludedFileIsMissing) {
  TempDir dir("teleop_sim_test");
  const std::string path = dir.write("includes.xml", "<mujoco><include file='missing_part.xml'/></mujoco>");
  const std::string message = error_of<std::runtime_error>([&] { MujocoModel::load(path); });
  EXPECT_NE(message.find(path), std::string::npos) << message;
  EXPECT_NE(message.find("missing_part.xml"), std::string::npos) << message;
}

TEST(MujocoModel, FindsIdsAndAddressesWhenNamesExist) {
  const MujocoModel sim = MujocoModel::load(model_path("panda.xml"));
  EXPECT_EQ(sim.joint_id("joint1"), 0);
  EXPECT_EQ(sim.joint_id("joint7"), 6);
  EXPECT_EQ(sim.actuator_id("motor4"), 3);
  EXPECT_EQ(sim.site_id("ee_site"), 0);
  EXPECT_EQ(sim.body_id("link7"), 8);
  EXPECT_EQ(sim.geom_id("link7_flange"), sim.model()->ngeom - 1);
  EXPECT_EQ(sim.keyframe_id("ready"), 0);
  EXPECT_EQ(sim.joint_qpos_address("joint5"), 4);
  EXPECT_EQ(sim.joint_dof_address("joint6"), 5);
}

TEST(MujocoModel, ThrowsNamingTheMissingNameWhenLookupFails) {
  const MujocoModel sim = MujocoModel::load(model_path("panda.xml"));
  for (const auto& [kind, lookup] : std::initializer_list<std::pair<std::string, std::function<void()>>>{
           {"joint", [&] { (void)sim.joint_id("elbow_joint"); }},
           {"site", [&] { (void)sim.site_id("elbow_joint"); }},
           {"actuator", [&] { (void)sim.actuator_id("elbow_joint"); }},
           {"body", [&] { (void)sim.body_id("elbow_joint"); }},
           {"geom", [&] { (void)sim.geom_id("elbow_joint"); }},
           {"keyframe", [&] { (void)sim.keyframe_id("elbow_joint"); }},
           {"joint", [&] { (void)sim.joint_qpos_address("elbow_joint"); }},
       }) {
    const std::string message = error_of<std::out_of_range>(lookup);
    EXPECT_NE(message.find("'elbow_joint'"), std::string::npos) << message;
    EXPECT_NE(message.find("no " + kind + " named"), std::string::npos) << message;
    EXPECT_NE(message.find("panda.xml"), std::string::npos) << message;
  }
}

TEST(MujocoModel, ResetsToKeyframeOrDefaultWhenAsked) {
  MujocoModel sim = MujocoModel::load(model_path("panda.xml"));
  sim.reset("ready");
  EXPECT_NEAR(sim.data()->qpos[3], -0.75 * M_PI, 1e-15);
  EXPECT_NEAR(sim.data()->site_xpos[2], 0.5903, 1e-4);  // derived quantities follow
  sim.reset();
  EXPECT_DOUBLE_EQ(sim.data()->qpos[3], 0.0);
  EXPECT_THROW(sim.reset("no_such_key"), std::out_of_range);
}

TEST(MujocoModel, MovesOwnershipWhenMoved) {
  MujocoModel first = MujocoModel::load(model_path("panda.xml"));
  const mjModel* model = first.model();
  MujocoModel second = std::move(first);
  EXPECT_EQ(second.model(), model);
  EXPECT_EQ(first.model(), nullptr);  // NOLINT(bugprone-use-after-move): checking the moved-from state
  MujocoModel third = MujocoModel::load(model_path("dual_arm.xml"));
  third = std::move(second);  // frees dual_arm's model and data
  EXPECT_EQ(third.model(), model);
  EXPECT_EQ(third.path(), model_path("panda.xml"));
}

}  // namespace
}  // namespace teleop::sim
