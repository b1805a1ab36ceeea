// Metric building blocks on synthetic signals with known answers.
#include "teleop/experiment/metrics.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

namespace teleop::experiment {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr Window kAll{-1e9, 1e9};

std::vector<double> times(size_t n, double dt, double t0 = 0) {
  std::vector<double> t(n);
  for (size_t i = 0; i < n; ++i) t[i] = t0 + static_cast<double>(i) * dt;
  return t;
}

TEST(Interpolate, IsLinearBetweenUnequalSampleTimesAndNanOutside) {
  const std::vector<double> t{0.0, 0.1, 0.4, 1.0};
  const std::vector<double> v{0.0, 1.0, 4.0, 1.0};
  const auto out = interpolate(t, v, {-0.1, 0.0, 0.05, 0.3, 0.4, 0.7, 1.0, 1.1});
  EXPECT_TRUE(std::isnan(out[0]));
  EXPECT_DOUBLE_EQ(out[1], 0.0);
  EXPECT_DOUBLE_EQ(out[2], 0.5);
  EXPECT_DOUBLE_EQ(out[3], 3.0);
  EXPECT_DOUBLE_EQ(out[4], 4.0);
  EXPECT_DOUBLE_EQ(out[5], 2.5);
  EXPECT_DOUBLE_EQ(out[6], 1.0);
  EXPECT_TRUE(std::isnan(out[7]));
}

TEST(Interpolate, RecoversALineSampledAtAnotherRateExactly) {
  // follower at 1 kHz with an offset clock phase, leader at 0.7 ms steps
  const auto tf = times(2000, 1e-3, 0.00031);
  std::vector<double> vf(tf.size());
  for (size_t i = 0; i < tf.size(); ++i) vf[i] = 3.0 * tf[i] - 1.0;
  const auto tl = times(2000, 0.7e-3, 0.001);
  const auto out = interpolate(tf, vf, tl);
  for (size_t i = 0; i < tl.size(); ++i) EXPECT_NEAR(out[i], 3.0 * tl[i] - 1.0, 1e-12) << i;
}

TEST(Norms, GiveTheEuclideanNormAndDistancePerSample) {
  const Axes a{std::vector<double>{3, 1}, {4, 2}, {0, 2}};
  const Axes b{std::vector<double>{0, 1}, {0, 2}, {0, 0}};
  EXPECT_EQ(norm(a), (std::vector<double>{5, 3}));
  EXPECT_EQ(distance(a, b), (std::vector<double>{5, 2}));
}

TEST(WindowStatistics, UseOnlyFiniteSamplesInsideTheWindow) {
  const std::vector<double> t{0, 1, 2, 3, 4};
  const std::vector<double> v{100, 1, kNaN, -3, 100};
  const Window w{1, 3};
  EXPECT_DOUBLE_EQ(mean_in(t, v, w), -1.0);
  EXPECT_DOUBLE_EQ(rms_in(t, v, w), std::sqrt(5.0));
  EXPECT_DOUBLE_EQ(peak_to_peak_in(t, v, w), 4.0);
  EXPECT_TRUE(std::isnan(mean_in(t, v, Window{10, 20})));
  EXPECT_TRUE(std::isnan(rms_in(t, v, Window{2, 2})));
  EXPECT_TRUE(std::isnan(peak_to_peak_in(t, v, Window{10, 20})));
}

TEST(MeanAbsoluteDeviation, IsZeroForALineAndNanWhereTheWindowDoesNotFit) {
  std::vector<double> x(30);
  for (size_t i = 0; i < x.size(); ++i) x[i] = 0.5 * static_cast<double>(i);
  const auto d = deviation_from_running_mean(x, 10);
  // centred window i-5 .. i+4 of a line: mean x_{i-0.5}, deviation half a step
  for (size_t i = 5; i + 5 <= x.size(); ++i) EXPECT_NEAR(d[i], 0.25, 1e-12) << i;
  for (size_t i : {0u, 4u, 26u, 29u}) EXPECT_TRUE(std::isnan(d[i])) << i;
  const std::vector<double> constant(20, 1.7);
  EXPECT_NEAR(mean_absolute_deviation_in(times(20, 1), constant, 10, kAll), 0.0, 1e-15);
}

TEST(MeanAbsoluteDeviation, MatchesTheClosedFormForASine) {
  // x = A sin(w t) at dt; the centred mean of 10 samples is g A sin(w t - phi) with
  // g = sin(5 w dt) / (10 sin(w dt / 2)), phi = w dt / 2, so x - x̄ is a sine of amplitude
  // A |1 - g e^{-i phi}| whose mean absolute value over whole periods is 2/pi of it
  const double amplitude = 0.01;
  const double dt = 1e-3;
  const double w = 2 * std::numbers::pi * 20.0;  // 20 Hz: 50 samples per period
  const size_t n = 5000;
  const auto t = times(n, dt);
  std::vector<double> x(n);
  for (size_t i = 0; i < n; ++i) x[i] = amplitude * std::sin(w * t[i]);
  const double g = std::sin(5 * w * dt) / (10 * std::sin(w * dt / 2));
  const double expected = 2 / std::numbers::pi * amplitude * std::abs(1.0 - g * std::polar(1.0, -w * dt / 2));
  // a window of exactly 4 s = 80 periods
  const double mad = mean_absolute_deviation_in(t, x, 10, Window{0.5, 4.5 - dt / 2});
  EXPECT_NEAR(mad, expected, 1e-3 * expected);
  EXPECT_GT(mad, 5e-4);  // not trivially small: five times the default stability limit
}

TEST(Fractions, CountAllSamplesAndNanWhenEmpty) {
  EXPECT_DOUBLE_EQ(fraction_at_least({0.5, 0.999, 1.0, kNaN}, 0.999), 0.5);
  EXPECT_DOUBLE_EQ(fraction_equal({2, 1, 2, 2}, 2), 0.75);
  EXPECT_TRUE(std::isnan(fraction_at_least({}, 1)));
  EXPECT_TRUE(std::isnan(fraction_equal({}, 1)));
}

TEST(MinFinite, SkipsNanAndIsNanWhenAllAre) {
  EXPECT_DOUBLE_EQ(min_finite({kNaN, 3, -2, kNaN}), -2);
  EXPECT_TRUE(std::isnan(min_finite({kNaN, kNaN})));
  EXPECT_TRUE(std::isnan(min_finite({})));
}

// --- the coupling thesis's fidelity metrics (§4.1) ---

Quaternion as_array(const Eigen::Quaterniond& q) { return {q.w(), q.x(), q.y(), q.z()}; }

Quaternion about(const Eigen::Vector3d& axis, double angle_rad) {
  return as_array(Eigen::Quaterniond(Eigen::AngleAxisd(angle_rad, axis.normalized())));
}

TEST(RotationDistance, IsZeroForIdenticalQuaternions) {
  EXPECT_EQ(rotation_distance({1, 0, 0, 0}, {1, 0, 0, 0}), 0.0);
  const Quaternion q = about({0.3, -0.5, 0.8}, 1.234);
  EXPECT_EQ(rotation_distance(q, q), 0.0);
}

TEST(RotationDistance, IsTwoForANinetyDegreeRotationAboutAnyAxis) {
  // by hand: q1 = (1, 0, 0, 0), q2 = (cos 45°, sin 45° n): q1 . q2 = cos 45° = 1/sqrt(2), so
  // theta = 2 sqrt(2 (1 - 1/2)) = 2
  const double c = std::sqrt(0.5);
  EXPECT_DOUBLE_EQ(rotation_distance({1, 0, 0, 0}, {c, c, 0, 0}), 2.0);
  EXPECT_DOUBLE_EQ(rotation_distance({1, 0, 0, 0}, {c, 0, c, 0}), 2.0);
  EXPECT_DOUBLE_EQ(rotation_distance({1, 0, 0, 0}, {c, 0, 0, c}), 2.0);
  // any axis, and between two rotations that are not the identity (bi-invariance)
  const Eigen::Quaterniond start(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()));
  for (const Eigen::Vector3d& axis : {Eigen::Vector3d(1, 1, 0), Eigen::Vector3d(-0.2, 0.9, 0.4)}) {
    const Eigen::Quaterniond turned = start * Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, axis.normalized()));
    EXPECT_NEAR(rotation_distance(as_array(start), as_array(turned)), 2.0, 1e-12);
  }
}

TEST(RotationDistance, GivesTheThesisValueForOneDegree) {
  // thesis §4.3.2: "a rotation about one degree on one axis ... leads to a rotation error of 0.0247"
  const double theta = rotation_distance({1, 0, 0, 0}, about({0, 0, 1}, M_PI / 180));
  EXPECT_NEAR(theta, 0.0247, 5e-5);
  EXPECT_NEAR(theta, 2 * std::sqrt(2.0) * std::sin(M_PI / 360), 1e-12);
}

TEST(RotationDistance, IsTheSameForQAndMinusQ) {
  const Quaternion q1 = about({0.2, 0.3, -0.9}, 0.4);
  const Quaternion q2 = about({-1, 0.5, 0.1}, 2.1);
  const Quaternion minus_q2{-q2[0], -q2[1], -q2[2], -q2[3]};
  const Quaternion minus_q1{-q1[0], -q1[1], -q1[2], -q1[3]};
  EXPECT_DOUBLE_EQ(rotation_distance(q1, minus_q2), rotation_distance(q1, q2));
  EXPECT_DOUBLE_EQ(rotation_distance(minus_q1, q2), rotation_distance(q1, q2));
  EXPECT_EQ(rotation_distance(q1, minus_q1), 0.0);
  EXPECT_GT(rotation_distance(q1, q2), 0.1);
}

TEST(Rmse, OfEqualErrorsIsThatError) {
  // thesis §4.1.1: "If every joint has the same absolute error size y°, the RMSE will be y"
  const std::vector<double> equal(7, 0.25);
  EXPECT_DOUBLE_EQ(rmse(equal), 0.25);
  const std::vector<double> signs{0.25, -0.25, 0.25, -0.25, -0.25, 0.25, 0.25};
  EXPECT_DOUBLE_EQ(rmse(signs), 0.25);
  EXPECT_DOUBLE_EQ(max_abs(signs), 0.25);
  // by hand: sqrt((9 + 16) / 2) = sqrt(12.5); the largest single error is 4
  EXPECT_DOUBLE_EQ(rmse(std::vector<double>{3.0, -4.0}), std::sqrt(12.5));
  EXPECT_DOUBLE_EQ(max_abs(std::vector<double>{3.0, -4.0}), 4.0);
  EXPECT_TRUE(std::isnan(rmse(std::vector<double>{})));
  EXPECT_TRUE(std::isnan(max_abs(std::vector<double>{})));
}

TEST(Summary, GivesMeanPopulationSdAndMaxOfTheFiniteSamplesInTheWindow) {
  const std::vector<double> t{0, 1, 2, 3, 4, 5};
  const std::vector<double> v{100, 1, kNaN, 3, 5, 100};
  const Summary s = summarize_in(t, v, {1, 4});
  EXPECT_EQ(s.samples, 3u);
  EXPECT_DOUBLE_EQ(s.mean, 3.0);
  EXPECT_DOUBLE_EQ(s.sd, std::sqrt(8.0 / 3.0));
  EXPECT_DOUBLE_EQ(s.max, 5.0);
  const Summary none = summarize_in(t, v, {10, 11});
  EXPECT_EQ(none.samples, 0u);
  EXPECT_TRUE(std::isnan(none.mean));
}

}  // namespace
}  // namespace teleop::experiment
