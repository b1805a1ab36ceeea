// The box task's plan (config/tasks/box_task.yaml) and the joint trajectories made from it.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "teleop/common/config.h"
#include "teleop/sim/mujoco_model.h"
#include "hand_trajectories.h"

namespace teleop::box_task {
namespace {

std::string source(const std::string& relative) { return std::string(TELEOP_SOURCE_DIR) + "/" + relative; }

const std::string kPlan = source("config/tasks/box_task.yaml");

/// A plan file in a scratch folder with the given waypoints; its models are the committed ones.
std::string write_plan(const std::string& name, const std::string& waypoints) {
  const auto dir = std::filesystem::temp_directory_path() / "teleop_box_plan_test";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / name).string();
  std::ofstream(path) << "models: {left: " << source("config/models/left_arm.xml")
                      << ", right: " << source("config/models/right_arm.xml") << "}\n"
                      << "rate_hz: 100\nbox: {half_width_m: 0.1, grip_height_m: 0.04}\nwaypoints:\n"
                      << waypoints;
  return path;
}

/// Rows of numbers of a CSV file, the header dropped.
std::vector<std::vector<double>> read_rows(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::stringstream cells(line);
    for (std::string cell; std::getline(cells, cell, ',');) row.push_back(std::stod(cell));
    rows.push_back(row);
  }
  return rows;
}

/// The message load_box_plan throws for `path` ("" when it loads).
std::string load_error(const std::string& path) {
  try {
    (void)load_box_plan(path);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(BoxPlan, ReadsTheCommittedPlanWhenLoaded) {
  const BoxPlan plan = load_box_plan(kPlan);
  ASSERT_GE(plan.waypoints.size(), 7u);
  EXPECT_EQ(plan.waypoints.front().phase, "approach");
  EXPECT_EQ(plan.waypoints.back().phase, "retreat");
  EXPECT_DOUBLE_EQ(plan.box_half_width_m, 0.1);
  EXPECT_TRUE(std::filesystem::exists(plan.left_model));
  EXPECT_TRUE(std::filesystem::exists(plan.right_model));
}

TEST(BoxPlan, PutsEachHandBesideItsFaceWhenAskedForAHandPosition) {
  BoxPlan plan;
  plan.box_half_width_m = 0.1;
  plan.grip_height_m = 0.04;
  const BoxWaypoint squeeze{"squeeze", 1.0, {0.35, 0.01, 0.8}, -0.005};
  EXPECT_TRUE(hand_position(plan, squeeze, Side::kLeft).isApprox(Eigen::Vector3d(0.35, 0.105, 0.84)));
  EXPECT_TRUE(hand_position(plan, squeeze, Side::kRight).isApprox(Eigen::Vector3d(0.35, -0.085, 0.84)));
}

TEST(BoxPlan, NamesFileAndKeyWhenTimesDoNotIncrease) {
  const std::string path = write_plan("backwards.yaml",
                                      "  - {phase: a, t_s: 2.0, box_m: [0.35, 0, 0.8], gap_m: 0.05}\n"
                                      "  - {phase: b, t_s: 1.0, box_m: [0.35, 0, 0.8], gap_m: 0.05}\n");
  const std::string error = load_error(path);
  EXPECT_NE(error.find("backwards.yaml"), std::string::npos) << error;
  EXPECT_NE(error.find("t_s"), std::string::npos) << error;
}

TEST(BoxPlan, RejectsAnUnknownKeyWhenLoaded) {
  const std::string path =
      write_plan("unknown.yaml", "  - {phase: a, t_s: 1.0, box_m: [0.35, 0, 0.8], gap_m: 0.05, grip: tight}\n");
  const std::string error = load_error(path);
  EXPECT_NE(error.find("grip"), std::string::npos) << error;
}

/// The committed plan's trajectories, planned once for all tests (slow under the sanitizers).
class HandTrajectories : public testing::Test {
 protected:
  static void SetUpTestSuite() {
    plan_ = new BoxPlan(load_box_plan(kPlan));
    trajectories_ = new std::array<HandTrajectory, 2>(plan_hand_trajectories(*plan_));
  }
  static void TearDownTestSuite() {
    delete trajectories_;
    delete plan_;
  }
  static BoxPlan* plan_;
  static std::array<HandTrajectory, 2>* trajectories_;
};
BoxPlan* HandTrajectories::plan_ = nullptr;
std::array<HandTrajectory, 2>* HandTrajectories::trajectories_ = nullptr;

TEST_F(HandTrajectories, RegeneratesTheCommittedCsvFilesWhenThePlanIsRun) {
  for (const HandTrajectory& hand : *trajectories_) {
    SCOPED_TRACE(side_name(hand.side));
    const std::string fresh = (std::filesystem::temp_directory_path() /
                               ("teleop_box_task_" + std::string(side_name(hand.side)) + ".csv"))
                                  .string();
    write_trajectory_csv(hand, fresh);
    const auto expected = read_rows(source("config/trajectories/box_task_" + std::string(side_name(hand.side)) + ".csv"));
    const auto actual = read_rows(fresh);
    ASSERT_EQ(actual.size(), expected.size()) << "regenerate with teleop_box_plan (docs/box_task.md)";
    for (size_t r = 0; r < actual.size(); ++r) {
      ASSERT_EQ(actual[r].size(), 15u) << "t_s, q_0..6, tau_op_0..6 (the plan asks for hand forces)";
      for (size_t c = 0; c < actual[r].size(); ++c) {
        ASSERT_NEAR(actual[r][c], expected[r][c], 1e-9) << "row " << r << " column " << c;
      }
    }
  }
}

TEST_F(HandTrajectories, ReachesEveryWaypointFacingTheBoxInsideTheJointLimitsWhenPlanned) {
  const BoxPlan& plan = *plan_;
  for (const HandTrajectory& hand : *trajectories_) {
    SCOPED_TRACE(side_name(hand.side));
    EXPECT_LT(hand.worst.position_m, 1e-3);
    EXPECT_LT(hand.worst.rotation_rad, 1e-3);
    EXPECT_GT(hand.min_limit_distance_rad, 0.1);
    // forward kinematics of the rows at the waypoints' times, on the model itself
    sim::MujocoModel arm = sim::MujocoModel::load(plan.model(hand.side));
    const int site = arm.site_id(std::string(side_name(hand.side)) + "_ee_site");
    const double towards_box = hand.side == Side::kLeft ? -1.0 : 1.0;
    for (const BoxWaypoint& waypoint : plan.waypoints) {
      SCOPED_TRACE(waypoint.phase);
      const auto row = static_cast<size_t>(std::lround(waypoint.t_s * plan.rate_hz));
      for (int j = 0; j < control::kDof; ++j) arm.data()->qpos[j] = hand.q_rad[row][j];
      mj_kinematics(arm.model(), arm.data());
      const Eigen::Vector3d flange = Eigen::Map<const Eigen::Vector3d>(arm.data()->site_xpos + 3 * site);
      EXPECT_LT((flange - hand_position(plan, waypoint, hand.side)).norm(), 1e-3);
      // the flange's z axis (third column of the site frame) points at the box face
      EXPECT_NEAR(arm.data()->site_xmat[9 * site + 5], towards_box, 1e-6);
      // the operator's torque exerts the waypoint's hand force at the flange: tau = J^T f
      mj_forward(arm.model(), arm.data());
      Eigen::Matrix<double, 3, Eigen::Dynamic, Eigen::RowMajor> jacobian(3, arm.model()->nv);
      mj_jacSite(arm.model(), arm.data(), jacobian.data(), nullptr, site);
      const Eigen::VectorXd expected = jacobian.transpose() * hand_force(waypoint, hand.side);
      for (int j = 0; j < control::kDof; ++j) EXPECT_NEAR(hand.tau_nm[row][j], expected[j], 1e-9) << "joint " << j;
    }
  }
}

}  // namespace
}  // namespace teleop::box_task
