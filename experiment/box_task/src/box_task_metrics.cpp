#include "teleop/box_task/box_task_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace teleop::box_task {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// field(sample) for every sample.
template <typename T, typename Field>
std::vector<T> per_sample(const BoxTaskSeries& series, Field&& field) {
  std::vector<T> values;
  values.reserve(series.samples.size());
  for (const BoxTaskSample& s : series.samples) values.push_back(field(s));
  return values;
}

/// Calls each_run(first, end) for every run [first, end) of true samples in `mask`.
template <typename EachRun>
void for_each_run(const std::vector<bool>& mask, EachRun&& each_run) {
  size_t k = 0;
  while (k < mask.size()) {
    if (!mask[k]) {
      ++k;
      continue;
    }
    const size_t first = k;
    while (k < mask.size() && mask[k]) ++k;
    each_run(first, k);
  }
}

/// From the first to the last sample of the run [first, end).
double run_duration_s(const BoxTaskSeries& series, size_t first, size_t end) {
  return series.samples[end - 1].t_s - series.samples[first].t_s;
}

/// Both hands touch the box.
bool held(const BoxTaskSample& s, double contact_n) {
  return s.left_squeeze_n >= contact_n && s.right_squeeze_n >= contact_n;
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

std::vector<bool> without_short_runs(const BoxTaskSeries& series, std::vector<bool> mask, double min_s) {
  for_each_run(mask, [&](size_t first, size_t end) {
    if (run_duration_s(series, first, end) < min_s) std::fill(mask.begin() + first, mask.begin() + end, false);
  });
  return mask;
}

std::vector<bool> unsupported_mask(const BoxTaskSeries& series, const BoxTaskThresholds& thresholds) {
  const double c = thresholds.contact_n;
  return without_short_runs(series, per_sample<bool>(series, [c](const BoxTaskSample& s) { return s.support_n < c; }),
                            thresholds.debounce_s);
}

std::vector<bool> carry_mask(const BoxTaskSeries& series, const BoxTaskThresholds& thresholds) {
  const double c = thresholds.contact_n;
  auto carried = [c](const BoxTaskSample& s) { return held(s, c) && s.support_n < c; };
  return without_short_runs(series, per_sample<bool>(series, carried), thresholds.debounce_s);
}

bool dropped(const BoxTaskSeries& series, const BoxTaskThresholds& thresholds) {
  const double c = thresholds.contact_n;
  const auto free = per_sample<bool>(series, [c](const BoxTaskSample& s) { return !held(s, c) && s.support_n < c; });
  bool fell = false;
  for_each_run(free, [&](size_t first, size_t end) {
    fell = fell || run_duration_s(series, first, end) > thresholds.debounce_s;
  });
  return fell;
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

double placed_time_s(const BoxTaskSeries& series, const BoxRegion& shelf, const BoxTaskThresholds& thresholds) {
  const std::vector<bool> unsupported = unsupported_mask(series, thresholds);
  double placed = kNaN;
  for (size_t k = series.samples.size(); k-- > 0;) {
    if (!shelf.contains(series.samples[k].box_m) || unsupported[k]) break;
    placed = series.samples[k].t_s;
  }
  return placed;
}

bool resting_at_end(const BoxTaskSeries& series, const BoxTaskThresholds& thresholds) {
  if (series.samples.empty() || unsupported_mask(series, thresholds).back()) return false;
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
  const std::vector<bool> carry = carry_mask(series, thresholds);
  const std::array<std::vector<double>, 2> squeeze = {
      per_sample<double>(series, [](const BoxTaskSample& s) { return s.left_squeeze_n; }),
      per_sample<double>(series, [](const BoxTaskSample& s) { return s.right_squeeze_n; })};
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
  const double placed = placed_time_s(series, shelf, thresholds);
  metrics.task_time_s = series.samples.empty() ? kNaN : placed - series.samples.front().t_s;
  for (const BoxTaskSample& s : series.samples) {
    metrics.max_arm_collision_n = std::max(metrics.max_arm_collision_n, s.arm_collision_n);
  }
  return metrics;
}

}  // namespace teleop::box_task
