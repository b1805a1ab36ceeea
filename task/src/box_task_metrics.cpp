#include "teleop/task/box_task_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace teleop::task {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

template <typename Field>
std::vector<double> column(const BoxTaskSeries& series, Field field) {
  std::vector<double> values;
  values.reserve(series.samples.size());
  for (const BoxTaskSample& s : series.samples) values.push_back(field(s));
  return values;
}

/// Time the samples in `mask` cover (each sample stands for the interval to the next one).
double masked_duration_s(const BoxTaskSeries& series, const std::vector<bool>& mask) {
  double total = 0;
  for (size_t k = 0; k + 1 < series.samples.size(); ++k) {
    if (mask[k]) total += series.samples[k + 1].t_s - series.samples[k].t_s;
  }
  return total;
}

}  // namespace

std::vector<bool> carry_mask(const BoxTaskSeries& series, double contact_n) {
  std::vector<bool> mask;
  mask.reserve(series.samples.size());
  for (const BoxTaskSample& s : series.samples) {
    mask.push_back(s.left_squeeze_n >= contact_n && s.right_squeeze_n >= contact_n && s.support_n < contact_n);
  }
  return mask;
}

bool dropped(const BoxTaskSeries& series, const BoxTaskThresholds& thresholds) {
  const double unset = std::numeric_limits<double>::quiet_NaN();
  double free_since_s = unset;  // start of the current run of unheld, unsupported samples
  for (const BoxTaskSample& s : series.samples) {
    const bool held = s.left_squeeze_n >= thresholds.contact_n && s.right_squeeze_n >= thresholds.contact_n;
    if (held || s.support_n >= thresholds.contact_n) {
      free_since_s = unset;
      continue;
    }
    if (std::isnan(free_since_s)) free_since_s = s.t_s;
    if (s.t_s - free_since_s > thresholds.drop_s) return true;
  }
  return false;
}

double variation_over(const std::vector<double>& values, const std::vector<bool>& mask) {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -lo;
  for (size_t k = 0; k < values.size(); ++k) {
    if (!mask[k] || !std::isfinite(values[k])) continue;
    lo = std::min(lo, values[k]);
    hi = std::max(hi, values[k]);
  }
  return hi >= lo ? hi - lo : kNaN;
}

Eigen::Vector3d box_in_hand_frame(const BoxTaskSample& sample) {
  const Eigen::Vector3d y = (sample.left_m - sample.right_m).normalized();
  const Eigen::Vector3d z = (Eigen::Vector3d::UnitZ() - Eigen::Vector3d::UnitZ().dot(y) * y).normalized();
  Eigen::Matrix3d frame;
  frame << y.cross(z), y, z;
  return frame.transpose() * (sample.box_m - 0.5 * (sample.left_m + sample.right_m));
}

double slip_mm(const BoxTaskSeries& series, const std::vector<bool>& mask) {
  const auto first = std::find(mask.begin(), mask.end(), true);
  if (first == mask.end()) return kNaN;
  const Eigen::Vector3d start = box_in_hand_frame(series.samples[static_cast<size_t>(first - mask.begin())]);
  double largest = 0;
  for (size_t k = 0; k < mask.size(); ++k) {
    if (mask[k]) largest = std::max(largest, (box_in_hand_frame(series.samples[k]) - start).norm());
  }
  return 1000.0 * largest;
}

double placed_time_s(const BoxTaskSeries& series, const BoxRegion& shelf, double contact_n) {
  double placed = kNaN;
  for (auto it = series.samples.rbegin(); it != series.samples.rend(); ++it) {
    if (!shelf.contains(it->box_m) || it->support_n < contact_n) break;
    placed = it->t_s;
  }
  return placed;
}

bool resting_at_end(const BoxTaskSeries& series, const BoxTaskThresholds& thresholds) {
  if (series.samples.empty() || series.samples.back().support_n < thresholds.contact_n) return false;
  const BoxTaskSample& last = series.samples.back();
  for (auto it = series.samples.rbegin(); it != series.samples.rend(); ++it) {
    if ((it->box_m - last.box_m).norm() >= thresholds.rest_motion_m) return false;
    if (last.t_s - it->t_s >= thresholds.rest_window_s) return true;
  }
  return false;  // the trace is shorter than the window
}

BoxTaskMetrics evaluate_box_task(const BoxTaskSeries& series, const BoxRegion& shelf,
                                 const BoxTaskThresholds& thresholds) {
  BoxTaskMetrics metrics;
  const std::vector<bool> carry = carry_mask(series, thresholds.contact_n);
  const std::array<std::vector<double>, 2> squeeze = {
      column(series, [](const BoxTaskSample& s) { return s.left_squeeze_n; }),
      column(series, [](const BoxTaskSample& s) { return s.right_squeeze_n; })};
  for (size_t hand = 0; hand < 2; ++hand) {
    metrics.squeeze_variation_n[hand] = variation_over(squeeze[hand], carry);
    metrics.squeeze_min_n[hand] = kNaN;
    for (size_t k = 0; k < carry.size(); ++k) {
      if (carry[k]) metrics.squeeze_min_n[hand] = std::fmin(metrics.squeeze_min_n[hand], squeeze[hand][k]);
    }
  }
  metrics.dropped = dropped(series, thresholds);
  metrics.carry_time_s = masked_duration_s(series, carry);
  metrics.slip_mm = slip_mm(series, carry);
  metrics.in_shelf = !series.samples.empty() && shelf.contains(series.samples.back().box_m);
  metrics.resting = resting_at_end(series, thresholds);
  metrics.success = metrics.in_shelf && metrics.resting && !metrics.dropped;
  const double placed = placed_time_s(series, shelf, thresholds.contact_n);
  metrics.task_time_s = series.samples.empty() ? kNaN : placed - series.samples.front().t_s;
  for (const BoxTaskSample& s : series.samples) {
    metrics.max_arm_collision_n = std::max(metrics.max_arm_collision_n, s.arm_collision_n);
  }
  return metrics;
}

}  // namespace teleop::task
