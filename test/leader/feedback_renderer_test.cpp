#include "feedback_renderer.h"

#include <gtest/gtest.h>

#include "allocation_counter.h"

namespace teleop::leader {
namespace {

FeedbackConfig config() {
  FeedbackConfig c;
  c.gain = 0.5;
  c.cutoff_hz = 0;  // no filter unless a test wants one
  c.max_torque_nm.fill(10.0);
  c.max_rate_nm_per_s = 0;
  c.fade_s = 0.1;
  return c;
}

JointVector constant(double v) {
  JointVector t{};
  t.fill(v);
  return t;
}

TEST(FeedbackRenderer, FadesInFromZeroAndAppliesTheGain) {
  FeedbackRenderer r(2, config(), 1000);
  const JointVector raw = constant(4.0);
  EXPECT_NEAR(r.render(raw, true)[0], 0.5 * 4.0 / 100, 1e-12) << "first cycle: 1/100 of the fade";
  for (int i = 0; i < 200; ++i) r.render(raw, true);
  EXPECT_DOUBLE_EQ(r.output()[0], 2.0);
  EXPECT_DOUBLE_EQ(r.fade(), 1.0);
}

TEST(FeedbackRenderer, FadesToZeroWithinTheFadeTimeWithoutAStepWhenTheSourceIsLost) {
  FeedbackRenderer r(1, config(), 1000);
  const JointVector raw = constant(8.0);
  for (int i = 0; i < 200; ++i) r.render(raw, true);
  double previous = r.output()[0];
  double largest_step = 0.0;
  int cycles = 0;
  while (r.output()[0] > 0.0) {
    r.render(raw, false);
    largest_step = std::max(largest_step, previous - r.output()[0]);
    previous = r.output()[0];
    ASSERT_LT(++cycles, 1000);
  }
  EXPECT_EQ(cycles, 100) << "fade_s = 0.1 s at 1 kHz";
  EXPECT_NEAR(largest_step, 4.0 / 100, 1e-12) << "linear fade: 1/100 of the torque per cycle";
}

TEST(FeedbackRenderer, SaturatesPerJointAndLimitsTheRate) {
  FeedbackConfig c = config();
  c.fade_s = 0;  // immediate
  c.max_torque_nm[1] = 1.0;
  c.max_rate_nm_per_s = 1000;  // 1 Nm per cycle
  FeedbackRenderer r(2, c, 1000);
  const JointVector raw = constant(30.0);  // gain 0.5: 15 Nm asked
  r.render(raw, true);
  EXPECT_DOUBLE_EQ(r.output()[0], 1.0) << "rate limited from zero";
  EXPECT_GE(r.rate_limited(), 1u);
  for (int i = 0; i < 50; ++i) r.render(raw, true);
  EXPECT_DOUBLE_EQ(r.output()[0], 10.0);
  EXPECT_DOUBLE_EQ(r.output()[1], 1.0);
  EXPECT_GT(r.saturations(), 0u);
  EXPECT_DOUBLE_EQ(r.peak_nm(), 10.0);
}

TEST(FeedbackRenderer, SmoothsWithTheLowPass) {
  FeedbackConfig c = config();
  c.fade_s = 0;
  c.cutoff_hz = 10;
  FeedbackRenderer r(1, c, 1000);
  r.render(constant(10.0), true);
  EXPECT_LT(r.output()[0], 0.5 * 10.0 * 0.1) << "one cycle of a 10 Hz low-pass passes ~6 %";
  for (int i = 0; i < 1000; ++i) r.render(constant(10.0), true);
  EXPECT_NEAR(r.output()[0], 5.0, 1e-6);
}

TEST(FeedbackRenderer, DoesNotAllocate) {
  FeedbackRenderer r(7, config(), 1000);
  test::ScopedAllocationCounter counter;
  for (int i = 0; i < 1000; ++i) r.render(constant(i * 0.01), i % 300 < 200);
  EXPECT_EQ(counter.count(), 0u);
}

}  // namespace
}  // namespace teleop::leader
