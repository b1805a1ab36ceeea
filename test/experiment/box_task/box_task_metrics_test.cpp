// The box task's metrics on synthetic traces whose answers are known by construction.

#include <gtest/gtest.h>

#include <cmath>

#include "teleop/box_task/box_task_metrics.h"

namespace teleop::box_task {
namespace {

const BoxRegion kShelf{{0.58, -0.09, 0.885}, {0.62, 0.09, 0.91}};

/// A sample with the box held between the hands (flanges 4 cm above its centre, 15 N each) and
/// nothing else touching it.
BoxTaskSample held(double t_s, const Eigen::Vector3d& box_m) {
  BoxTaskSample s;
  s.t_s = t_s;
  s.box_m = box_m;
  s.left_m = box_m + Eigen::Vector3d(0, 0.1, 0.04);
  s.right_m = box_m + Eigen::Vector3d(0, -0.1, 0.04);
  s.left_squeeze_n = 15;
  s.right_squeeze_n = 15;
  return s;
}

/// The same box resting on a support, the hands away.
BoxTaskSample resting(double t_s, const Eigen::Vector3d& box_m) {
  BoxTaskSample s = held(t_s, box_m);
  s.left_m.y() += 0.05;
  s.right_m.y() -= 0.05;
  s.left_squeeze_n = 0;
  s.right_squeeze_n = 0;
  s.support_n = 9.81;
  return s;
}

/// A whole task at 10 ms: in the socket until 1 s, carried from 1 s to 3 s (straight to the
/// shelf), set down on the shelf floor at 3 s, released, resting until 4 s.
BoxTaskSeries ideal_task() {
  BoxTaskSeries series;
  const Eigen::Vector3d socket(0.35, 0, 0.80);
  const Eigen::Vector3d shelf(0.60, 0, 0.89);
  for (int k = 0; k <= 400; ++k) {
    const double t = 0.01 * k;
    if (t < 1.0) series.append(resting(t, socket));
    else if (t < 3.0) series.append(held(t, socket + (t - 1.0) / 2.0 * (shelf - socket)));
    else series.append(resting(t, shelf));
  }
  return series;
}

TEST(BoxTaskMetrics, ReportsSuccessAndThePlacingTimeWhenTheBoxEndsRestingInTheShelf) {
  const BoxTaskMetrics m = evaluate_box_task(ideal_task(), kShelf);
  EXPECT_TRUE(m.in_shelf);
  EXPECT_TRUE(m.resting);
  EXPECT_FALSE(m.dropped);
  EXPECT_TRUE(m.success);
  EXPECT_NEAR(m.task_time_s, 3.0, 1e-9);
  EXPECT_NEAR(m.carry_time_s, 2.0, 1e-9);
  EXPECT_DOUBLE_EQ(m.squeeze_variation_n[0], 0.0);
  EXPECT_DOUBLE_EQ(m.squeeze_min_n[1], 15.0);
  EXPECT_NEAR(m.slip_mm, 0.0, 1e-9);
  EXPECT_DOUBLE_EQ(m.max_arm_collision_n, 0.0);
}

TEST(BoxTaskMetrics, TakesTheSqueezeVariationOverTheCarryOnlyWhenTheForceChangesOutsideIt) {
  BoxTaskSeries series = ideal_task();
  for (BoxTaskSample& s : series.samples) {
    if (s.t_s >= 1.5 && s.t_s < 2.0) s.left_squeeze_n = 22;  // during the carry: counts
    if (s.t_s < 1.0) s.right_squeeze_n = 40;                 // box still on its support: does not
  }
  const BoxTaskMetrics m = evaluate_box_task(series, kShelf);
  EXPECT_DOUBLE_EQ(m.squeeze_variation_n[0], 7.0);
  EXPECT_DOUBLE_EQ(m.squeeze_variation_n[1], 0.0);
}

TEST(BoxTaskMetrics, MeasuresSlipInTheHandsFrameWhenTheBoxSlidesDownBetweenThem) {
  BoxTaskSeries series = ideal_task();
  for (BoxTaskSample& s : series.samples) {
    if (s.t_s >= 1.0 && s.t_s < 3.0) s.box_m.z() -= 0.004 * (s.t_s - 1.0);  // 4 mm/s down the flanges
  }
  EXPECT_NEAR(evaluate_box_task(series, kShelf).slip_mm, 0.004 * 1.99 * 1000, 1e-6);
}

TEST(BoxTaskMetrics, IgnoresMotionOfTheHandsAndBoxTogetherWhenTheHandFrameTurns) {
  // hands and box turned together by 30 degrees about z and moved: no slip
  BoxTaskSample a = held(0.0, {0.4, 0.0, 0.9});
  BoxTaskSample b = a;
  const Eigen::AngleAxisd turn(0.5236, Eigen::Vector3d::UnitZ());
  const Eigen::Vector3d shift(0.1, -0.05, 0.02);
  for (Eigen::Vector3d* p : {&b.box_m, &b.left_m, &b.right_m}) *p = turn * *p + shift;
  EXPECT_LT((box_in_hand_frame(a) - box_in_hand_frame(b)).norm(), 1e-12);
  EXPECT_NEAR(box_in_hand_frame(a).z(), -0.04, 1e-12);  // the box hangs 4 cm below the grip
}

TEST(BoxTaskMetrics, ReportsADropAndNoSuccessWhenTheBoxFallsFreeForLongerThanTheThreshold) {
  BoxTaskSeries series = ideal_task();
  for (BoxTaskSample& s : series.samples) {
    if (s.t_s >= 2.0 && s.t_s < 2.1) s.left_squeeze_n = s.right_squeeze_n = 0;  // 100 ms free fall
  }
  const BoxTaskMetrics m = evaluate_box_task(series, kShelf);
  EXPECT_TRUE(m.dropped);
  EXPECT_FALSE(m.success);
}

TEST(BoxTaskMetrics, IgnoresASingleUnsupportedSampleWhenTheBoxSettlesAtTheStart) {
  BoxTaskSeries series = ideal_task();
  series.samples.front().support_n = 0;  // the first step, before the contact builds up
  EXPECT_FALSE(dropped(series, {}));
}

TEST(BoxTaskMetrics, IgnoresAOneSampleSupportFlickerWhenTheHandsReleaseThePlacedBox) {
  BoxTaskSeries series = ideal_task();
  for (BoxTaskSample& s : series.samples) {
    if (s.t_s >= 3.0 && s.t_s < 3.2) s.left_squeeze_n = s.right_squeeze_n = 5;  // still touching
  }
  series.samples[310].support_n = 0;  // the box lifts off the floor for one sample at 3.1 s
  const BoxTaskMetrics m = evaluate_box_task(series, kShelf);
  EXPECT_NEAR(m.task_time_s, 3.0, 1e-9);
  EXPECT_DOUBLE_EQ(m.squeeze_min_n[0], 15.0);  // the flicker is not part of the carry
  EXPECT_NEAR(m.carry_time_s, 2.0, 1e-9);
  EXPECT_TRUE(m.success);
}

TEST(BoxTaskMetrics, CountsAHeldRunLongerThanTheDebounceAsCarry) {
  BoxTaskSeries series = ideal_task();
  for (size_t k = 310; k < 315; ++k) {  // 40 ms lifted off the floor again, held at 5 N
    series.samples[k].support_n = 0;
    series.samples[k].left_squeeze_n = series.samples[k].right_squeeze_n = 5;
  }
  const BoxTaskMetrics m = evaluate_box_task(series, kShelf);
  EXPECT_DOUBLE_EQ(m.squeeze_min_n[0], 5.0);
  EXPECT_NEAR(m.task_time_s, 3.15, 1e-9);
}

TEST(BoxTaskMetrics, FailsWhenTheBoxStopsShortOfTheShelfOrStillMoves) {
  BoxTaskSeries short_of_it = ideal_task();
  for (BoxTaskSample& s : short_of_it.samples) {
    if (s.t_s >= 3.0) s.box_m.x() = 0.55;  // on the floor's front edge, not inside
  }
  const BoxTaskMetrics outside = evaluate_box_task(short_of_it, kShelf);
  EXPECT_FALSE(outside.in_shelf);
  EXPECT_FALSE(outside.success);
  EXPECT_TRUE(std::isnan(outside.task_time_s));

  BoxTaskSeries sliding = ideal_task();
  for (BoxTaskSample& s : sliding.samples) {
    if (s.t_s >= 3.0) s.box_m.x() = 0.59 + 0.01 * (s.t_s - 3.0);  // still creeping at 1 cm/s
  }
  const BoxTaskMetrics moving = evaluate_box_task(sliding, kShelf);
  EXPECT_TRUE(moving.in_shelf);
  EXPECT_FALSE(moving.resting);
  EXPECT_FALSE(moving.success);
}

TEST(BoxTaskMetrics, ReportsTheLargestArmCollisionForceWhenAnArmHitsTheShelf) {
  BoxTaskSeries series = ideal_task();
  series.samples[250].arm_collision_n = 12.5;
  EXPECT_DOUBLE_EQ(evaluate_box_task(series, kShelf).max_arm_collision_n, 12.5);
}

TEST(BoxTaskMetrics, GivesNanAndFalseWhenTheTraceIsEmpty) {
  const BoxTaskMetrics m = evaluate_box_task({}, kShelf);
  EXPECT_FALSE(m.success);
  EXPECT_TRUE(std::isnan(m.task_time_s));
  EXPECT_TRUE(std::isnan(m.slip_mm));
  EXPECT_TRUE(std::isnan(m.squeeze_variation_n[0]));
}

}  // namespace
}  // namespace teleop::box_task
