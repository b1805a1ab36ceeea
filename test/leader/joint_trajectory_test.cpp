#include "joint_trajectory.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "allocation_counter.h"
#include "teleop/common/config.h"
#include "test_helpers.h"

namespace teleop::leader {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;

// two joints; times start at 10 s to show they are taken relative to the first row
constexpr const char* kTwoJoints =
    "t_s,q_0,q_1\n"
    "10.0,0.0,1.0\n"
    "10.5,1.0,1.0\n"
    "11.0,1.0,3.0\n";

class JointTrajectoryTest : public ::testing::Test {
 protected:
  JointTrajectory load(const std::string& text, size_t joints = 2, const std::string& prefix = "q_") {
    return JointTrajectory::load_csv(dir_.write("trajectory.csv", text), joints, prefix);
  }
  // the error loading `text` throws
  std::string error(const std::string& text, size_t joints = 2) {
    return test::error_of<ConfigError>([&] { load(text, joints); });
  }
  std::string file() const { return dir_.path("trajectory.csv"); }

  test::TempDir dir_{"joint_trajectory_test"};
  JointVector q_{};
  JointVector dq_{};
};

TEST_F(JointTrajectoryTest, InterpolatesLinearlyBetweenRows) {
  const auto trajectory = load(kTwoJoints);
  EXPECT_EQ(trajectory.rows(), 3u);
  EXPECT_DOUBLE_EQ(trajectory.duration_s(), 1.0);
  trajectory.sample(0.25, q_, dq_);
  EXPECT_DOUBLE_EQ(q_[0], 0.5);
  EXPECT_DOUBLE_EQ(q_[1], 1.0);
  trajectory.sample(0.75, q_, dq_);
  EXPECT_DOUBLE_EQ(q_[0], 1.0);
  EXPECT_DOUBLE_EQ(q_[1], 2.0);
  trajectory.sample(0.5, q_, dq_);  // exactly on a row
  EXPECT_DOUBLE_EQ(q_[0], 1.0);
  EXPECT_DOUBLE_EQ(q_[1], 1.0);
}

TEST_F(JointTrajectoryTest, ComputesVelocitiesByFiniteDifferencesWhenAbsent) {
  // q = t^2 on a uniform grid: central differences are exact inside, one-sided at the ends
  const auto trajectory = load("t_s,q_0\n0.0,0.0\n0.1,0.01\n0.2,0.04\n0.3,0.09\n", 1);
  trajectory.sample(0.1, q_, dq_);
  EXPECT_NEAR(dq_[0], 0.2, 1e-12);
  trajectory.sample(0.15, q_, dq_);  // between rows the velocity is interpolated too
  EXPECT_NEAR(dq_[0], 0.3, 1e-12);
  trajectory.sample(0.0, q_, dq_);
  EXPECT_NEAR(dq_[0], 0.1, 1e-12) << "forward difference at the first row";
}

TEST_F(JointTrajectoryTest, UsesRecordedVelocitiesWhenPresent) {
  const auto trajectory = load("t_s,q_0,dq_0\n0,0,5\n1,1,7\n", 1);
  trajectory.sample(0.5, q_, dq_);
  EXPECT_DOUBLE_EQ(q_[0], 0.5);
  EXPECT_DOUBLE_EQ(dq_[0], 6.0);
}

TEST_F(JointTrajectoryTest, InterpolatesTheOperatorsIntendedTorqueAndHoldsItAtTheEnds) {
  const auto trajectory = load("t_s,q_0,tau_op_0\n0,0,2\n1,0,6\n", 1);
  JointVector tau{};
  trajectory.sample_torque(0.25, tau);
  EXPECT_DOUBLE_EQ(tau[0], 3.0);
  trajectory.sample_torque(-1.0, tau);
  EXPECT_DOUBLE_EQ(tau[0], 2.0);
  trajectory.sample_torque(5.0, tau);
  EXPECT_DOUBLE_EQ(tau[0], 6.0) << "the operator keeps pressing after the recording ends";
}

TEST_F(JointTrajectoryTest, IntendsNoTorqueWithoutTorqueColumns) {
  const auto trajectory = load(kTwoJoints);
  JointVector tau{};
  tau.fill(9.0);
  trajectory.sample_torque(0.5, tau);
  EXPECT_EQ(tau[0], 0.0);
  EXPECT_EQ(tau[1], 0.0);
}

TEST_F(JointTrajectoryTest, HoldsTheFirstRowBeforeAndTheLastRowAfterTheEnd) {
  const auto trajectory = load(kTwoJoints);
  trajectory.sample(-1.0, q_, dq_);
  EXPECT_DOUBLE_EQ(q_[0], 0.0);
  EXPECT_DOUBLE_EQ(q_[1], 1.0);
  EXPECT_DOUBLE_EQ(dq_[0], 0.0);
  trajectory.sample(5.0, q_, dq_);
  EXPECT_DOUBLE_EQ(q_[0], 1.0);
  EXPECT_DOUBLE_EQ(q_[1], 3.0);
  EXPECT_DOUBLE_EQ(dq_[0], 0.0);
  EXPECT_DOUBLE_EQ(dq_[1], 0.0);
  trajectory.sample(std::nan(""), q_, dq_);
  EXPECT_DOUBLE_EQ(q_[0], 0.0) << "a NaN time holds the start";
}

TEST_F(JointTrajectoryTest, WrapsAroundWhenLooping) {
  auto trajectory = load(kTwoJoints);
  trajectory.set_loop(true);
  trajectory.sample(2.25, q_, dq_);  // two periods of 1 s, then 0.25 s in
  EXPECT_NEAR(q_[0], 0.5, 1e-12);
  // moving, not held: halfway between row 0's forward difference (2) and row 1's central one (1)
  EXPECT_NEAR(dq_[0], 1.5, 1e-12);
  trajectory.sample(1.75, q_, dq_);
  EXPECT_NEAR(q_[1], 2.0, 1e-12);
}

TEST_F(JointTrajectoryTest, ReadsTheLeadersTraceIgnoringOtherColumns) {
  const auto trajectory = load(
      "t_s,cycle,q_cmd_0,q_dev_0,q_dev_1,overruns\n"
      "0.000,0,9,0.1,0.2,0\n"
      "0.001,1,9,0.3,0.4,0\n",
      2, "q_dev_");
  trajectory.sample(0.0005, q_, dq_);
  EXPECT_NEAR(q_[0], 0.2, 1e-12);
  EXPECT_NEAR(q_[1], 0.3, 1e-12);
  EXPECT_NEAR(dq_[0], 200.0, 1e-9);
}

TEST_F(JointTrajectoryTest, DoesNotAllocateWhenSampling) {
  auto trajectory = load(kTwoJoints);
  trajectory.set_loop(true);
  test::ScopedAllocationCounter allocations;
  for (double t = -0.5; t < 3.0; t += 0.01) trajectory.sample(t, q_, dq_);
  EXPECT_EQ(allocations.count(), 0u);
}

TEST_F(JointTrajectoryTest, NamesTheFileAndColumnOfAMissingColumn) {
  EXPECT_EQ(error("t_s,q_0\n0,0\n1,1\n"), file() + ":1: q_1: column missing from the header");
  EXPECT_EQ(error("time,q_0,q_1\n0,0,0\n1,1,1\n"), file() + ":1: t_s: column missing from the header");
  EXPECT_EQ(error("t_s,q_0,q_1,dq_0\n0,0,0,0\n1,1,1,1\n"), file() + ":1: dq_1: column missing from the header");
}

TEST_F(JointTrajectoryTest, NamesTheLineAndColumnOfABadNumber) {
  EXPECT_EQ(error("t_s,q_0,q_1\n0,0,0\n1,x1,1\n"), file() + ":3: q_0: 'x1' is not a number");
  EXPECT_EQ(error("t_s,q_0,q_1\n0,0,\n1,1,1\n"), file() + ":2: q_1: '' is not a number");
  EXPECT_EQ(error("t_s,q_0,q_1\n0,0,nan\n1,1,1\n"), file() + ":2: q_1: 'nan' is not finite");
  EXPECT_EQ(error("t_s,q_0,q_1\n0,0,0\ninf,1,1\n"), file() + ":3: t_s: 'inf' is not finite");
  EXPECT_EQ(error("t_s,q_0,q_1\n0,0,0\n1,1\n"), file() + ":3: row: 2 fields, the header has 3");
}

TEST_F(JointTrajectoryTest, NamesTheLineOfATimeThatDoesNotIncrease) {
  EXPECT_THAT(error("t_s,q_0,q_1\n0,0,0\n1,1,1\n1,2,2\n"),
              AllOf(HasSubstr(file() + ":4: t_s: "), HasSubstr("is not after the previous row's")));
}

TEST_F(JointTrajectoryTest, RefusesFewerThanTwoRows) {
  EXPECT_THAT(error("t_s,q_0,q_1\n0,0,0\n"), HasSubstr(file() + ":2: rows: 1 data row(s)"));
  EXPECT_EQ(error(""), file() + ":1: header: missing (the file is empty)");
}

TEST_F(JointTrajectoryTest, NamesAFileThatCannotBeOpened) {
  const std::string missing = dir_.path("absent.csv");
  EXPECT_EQ(test::error_of<ConfigError>([&] { JointTrajectory::load_csv(missing, 2); }),
            missing + ": file: cannot be opened");
}

}  // namespace
}  // namespace teleop::leader
