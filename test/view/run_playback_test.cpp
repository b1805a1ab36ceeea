#include "teleop/view/run_playback.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "teleop/view/view_model.h"

namespace teleop::view {
namespace {

namespace fs = std::filesystem;

class RunPlaybackTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = fs::temp_directory_path() / ("teleop-view-playback-" + std::to_string(::getpid()) + "-" +
                                       ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir);
  }
  void TearDown() override { fs::remove_all(dir); }
  void write(const std::string& name, const std::string& text) const { std::ofstream(dir / name) << text; }
  static ViewModelSpec spec(const std::string& node) {
    return read_view_model(std::string(TELEOP_SOURCE_DIR) + "/config/nodes/" + node);
  }
  fs::path dir;
};

TEST_F(RunPlaybackTest, TheFollowersTraceIsInterpolatedAndTheTwinsAlignedOnTheWallClock) {
  write("follower.csv",
        "t_s,wall_s,lateness_us,x_x,x_y,x_z,f_ext_x,f_ext_y,f_ext_z,q_0,q_1,q_2,q_3,q_4,q_5,q_6\n"
        "0.5,100.0,1,0.5,0,0.7,-10,0,0,0,0,0,-2,0,3,0\n"
        "1.5,101.0,1,0.5,0,0.7,-30,0,0,1,0,0,-2,0,3,0\n");
  // the twin started half a second after the follower (its own t_s restarts at 0)
  write("twin.csv",
        "t_s,wall_s,lateness_us,q_0,q_1,q_2,q_3,q_4,q_5,q_6\n"
        "0.0,100.5,1,2,0,0,-2,0,3,0\n"
        "0.5,101.0,1,3,0,0,-2,0,3,0\n");
  PosedScene scene(spec("follower.yaml"));
  const RunPlayback run(dir.string(), scene, true, false);
  EXPECT_DOUBLE_EQ(run.duration_s(), 1.0);
  EXPECT_EQ(run.sources(), "follower.csv, twin.csv");

  run.pose(scene, 0.25);
  EXPECT_TRUE(scene.posed(Layer::kFollower));
  EXPECT_NEAR(scene.data(Layer::kFollower)->qpos[0], 0.25, 1e-12);
  // before the twin's first row: no ghost
  EXPECT_FALSE(scene.posed(Layer::kTwin));
  const std::vector<ForceArrow> forces = run.forces(0.25);
  ASSERT_EQ(forces.size(), 1u);
  EXPECT_NEAR(forces[0].force[0], -15.0, 1e-12);
  EXPECT_NEAR(forces[0].from[2], 0.7, 1e-12);

  run.pose(scene, 0.75);
  EXPECT_NEAR(scene.data(Layer::kFollower)->qpos[0], 0.75, 1e-12);
  ASSERT_TRUE(scene.posed(Layer::kTwin));
  EXPECT_NEAR(scene.data(Layer::kTwin)->qpos[0], 2.5, 1e-12);
  // past the end: the last row
  run.pose(scene, 5.0);
  EXPECT_NEAR(scene.data(Layer::kFollower)->qpos[0], 1.0, 1e-12);
}

TEST_F(RunPlaybackTest, TwoArmsReadTheirPrefixedColumnsAndTheBoxItsPosition) {
  std::string header = "t_s,wall_s,lateness_us,box_x,box_y,box_z";
  std::string row0 = "0,10,0,0.35,0,0.80";
  std::string row1 = "1,11,0,0.55,0,0.90";
  for (const char* arm : {"left", "right"}) {
    for (int i = 0; i < 7; ++i) {
      header += std::string(",") + arm + "_q_" + std::to_string(i);
      row0 += i == 3 ? ",-2" : ",0";
      row1 += i == 3 ? ",-2" : (i == 0 ? ",0.4" : ",0");
    }
  }
  write("follower.csv", header + "\n" + row0 + "\n" + row1 + "\n");
  PosedScene scene(spec("follower_box_task.yaml"));
  const RunPlayback run(dir.string(), scene, true, false);
  EXPECT_EQ(run.sources(), "follower.csv");
  run.pose(scene, 0.5);
  const mjModel* m = scene.model();
  const mjData* d = scene.data(Layer::kFollower);
  EXPECT_NEAR(d->qpos[m->jnt_qposadr[mj_name2id(m, mjOBJ_JOINT, "left_joint1")]], 0.2, 1e-12);
  EXPECT_NEAR(d->qpos[m->jnt_qposadr[mj_name2id(m, mjOBJ_JOINT, "right_joint1")]], 0.2, 1e-12);
  const int box = scene.free_bodies()[0].qpos;
  EXPECT_NEAR(d->qpos[box], 0.45, 1e-12);
  EXPECT_NEAR(d->qpos[box + 2], 0.85, 1e-12);
  EXPECT_NEAR(d->qpos[box + 3], 1.0, 1e-12);  // the keyframe's orientation
}

TEST_F(RunPlaybackTest, ATraceWithoutTheArmsJointsIsRefusedNamingFileAndColumn) {
  write("follower.csv", "t_s,wall_s,lateness_us,x_x\n0,1,0,0.5\n");
  PosedScene scene(spec("follower.yaml"));
  try {
    RunPlayback run(dir.string(), scene, true, false);
    FAIL() << "expected a TraceError";
  } catch (const experiment::TraceError& e) {
    EXPECT_NE(std::string(e.what()).find("follower.csv: no column 'q_0'"), std::string::npos) << e.what();
  }
  fs::remove(dir / "follower.csv");
  EXPECT_THROW(RunPlayback(dir.string(), scene, true, false), experiment::TraceError);
}

}  // namespace
}  // namespace teleop::view
