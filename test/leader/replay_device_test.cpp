#include "replay_device.h"

#include <gtest/gtest.h>

#include <limits>

#include "allocation_counter.h"
#include "test_helpers.h"

namespace teleop::leader {
namespace {

// one joint moving 0 -> 1 rad over 1 s
class ReplayDeviceTest : public ::testing::Test {
 protected:
  ReplayDevice device(double period_s = 0.25) {
    return ReplayDevice(JointTrajectory::load_csv(dir_.write("ramp.csv", "t_s,q_0\n0,0\n1,1\n"), 1), period_s);
  }

  test::TempDir dir_{"replay_device_test"};
  DeviceState state_{};
  const JointVector no_feedback_{};
};

TEST_F(ReplayDeviceTest, AdvancesOnePeriodPerWrite) {
  auto replay = device();
  EXPECT_STREQ(replay.name(), "replay");
  EXPECT_EQ(replay.joints(), 1u);
  ASSERT_TRUE(replay.read(state_));
  EXPECT_DOUBLE_EQ(state_.q_rad[0], 0.0);
  ASSERT_TRUE(replay.read(state_));
  EXPECT_DOUBLE_EQ(state_.q_rad[0], 0.0) << "reading does not advance the time";
  for (int i = 1; i <= 3; ++i) {
    ASSERT_TRUE(replay.write(no_feedback_));
    ASSERT_TRUE(replay.read(state_));
    EXPECT_DOUBLE_EQ(state_.q_rad[0], 0.25 * i);
    EXPECT_DOUBLE_EQ(state_.dq_radps[0], 1.0);
  }
  EXPECT_DOUBLE_EQ(replay.time_s(), 0.75);
}

TEST_F(ReplayDeviceTest, HoldsTheLastPoseAfterTheEndWithNoOperatorTorque) {
  auto replay = device();
  for (int i = 0; i < 10; ++i) ASSERT_TRUE(replay.write(no_feedback_));
  state_.tau_operator_nm.fill(3.0);
  ASSERT_TRUE(replay.read(state_));
  EXPECT_DOUBLE_EQ(state_.q_rad[0], 1.0);
  EXPECT_DOUBLE_EQ(state_.dq_radps[0], 0.0);
  EXPECT_DOUBLE_EQ(state_.tau_operator_nm[0], 0.0);
}

TEST_F(ReplayDeviceTest, RecordsTheLargestFeedbackAndRefusesNonFinite) {
  auto replay = device();
  JointVector feedback{};
  feedback[0] = -4.0;
  ASSERT_TRUE(replay.write(feedback));
  feedback[0] = 2.0;
  ASSERT_TRUE(replay.write(feedback));
  EXPECT_DOUBLE_EQ(replay.max_feedback_nm(), 4.0);
  feedback[0] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(replay.write(feedback));
  feedback[0] = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(replay.write(feedback));
  EXPECT_DOUBLE_EQ(replay.max_feedback_nm(), 4.0);
  EXPECT_DOUBLE_EQ(replay.time_s(), 1.0) << "a refused write still ends the period";
}

TEST_F(ReplayDeviceTest, RefusesAPeriodThatIsNotPositive) {
  EXPECT_THROW(device(0.0), std::invalid_argument);
  EXPECT_THROW(device(std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
}

TEST_F(ReplayDeviceTest, DoesNotAllocateWhenReadOrWritten) {
  auto replay = device(0.001);
  JointVector feedback{};
  feedback[0] = 1.0;
  test::ScopedAllocationCounter allocations;
  for (int i = 0; i < 1500; ++i) {
    ASSERT_TRUE(replay.read(state_));
    ASSERT_TRUE(replay.write(feedback));
  }
  EXPECT_EQ(allocations.count(), 0u);
}

}  // namespace
}  // namespace teleop::leader
