#include "teleop/common/lowpass.h"

#include <gtest/gtest.h>

#include <cmath>

namespace teleop {
namespace {

JointVector filled(double v, size_t n) {
  JointVector x{};
  for (size_t i = 0; i < n; ++i) x[i] = v;
  return x;
}

TEST(LowPassFilter, ReachesSixtyThreePercentAfterOneTimeConstantWhenStepped) {
  constexpr double kCutoff = 10.0;
  constexpr double kRate = 1000.0;
  LowPassFilter f(kCutoff, kRate);
  const double rc = 1.0 / (2.0 * M_PI * kCutoff);
  const auto samples_per_rc = static_cast<int>(std::lround(rc * kRate));  // 16
  const JointVector step = filled(1.0, 3);
  double y = 0.0;
  double previous = 0.0;
  for (int k = 0; k < samples_per_rc; ++k) {
    y = f.apply(step, 3)[0];
    ASSERT_GT(y, previous);  // rises monotonically
    ASSERT_LT(y, 1.0);       // never overshoots
    previous = y;
  }
  EXPECT_NEAR(y, 1.0 - std::exp(-1.0), 0.02);
  for (int k = 0; k < 20 * samples_per_rc; ++k) y = f.apply(step, 3)[0];
  EXPECT_NEAR(y, 1.0, 1e-6);
}

TEST(LowPassFilter, AlphaMatchesDiscretisedRcWhenCutoffValid) {
  const LowPassFilter f(50.0, 1000.0);
  const double rc = 1.0 / (2.0 * M_PI * 50.0);
  EXPECT_DOUBLE_EQ(f.alpha(), 0.001 / (rc + 0.001));
  EXPECT_GT(f.alpha(), 0.0);
  EXPECT_LT(f.alpha(), 1.0);
}

TEST(LowPassFilter, PassesInputThroughWhenCutoffDisabled) {
  for (double cutoff : {0.0, -5.0, 500.0, 800.0}) {  // off, negative, at and above Nyquist (500 Hz)
    LowPassFilter f(cutoff, 1000.0);
    EXPECT_EQ(f.alpha(), 1.0) << cutoff;
    const JointVector x = filled(0.75, 2);
    const JointVector& y = f.apply(x, 2);
    EXPECT_EQ(y[0], 0.75) << cutoff;
    EXPECT_EQ(y[1], 0.75) << cutoff;
  }
}

TEST(LowPassFilter, FiltersOnlyTheFirstNJointsWhenApplied) {
  LowPassFilter f(0.0, 1000.0);
  const JointVector x = filled(2.0, 4);
  const JointVector& y = f.apply(x, 2);
  EXPECT_EQ(y[0], 2.0);
  EXPECT_EQ(y[1], 2.0);
  EXPECT_EQ(y[2], 0.0);
  EXPECT_EQ(y[3], 0.0);
}

TEST(LowPassFilter, FiltersEachJointIndependently) {
  LowPassFilter f(10.0, 1000.0);
  JointVector x{};
  x[0] = 1.0;
  x[1] = -2.0;
  const JointVector& y = f.apply(x, 2);
  EXPECT_DOUBLE_EQ(y[0], f.alpha());
  EXPECT_DOUBLE_EQ(y[1], -2.0 * f.alpha());
}

}  // namespace
}  // namespace teleop
