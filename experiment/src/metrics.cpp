#include "teleop/experiment/metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace teleop::experiment {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// calls f(value) for each finite value whose time is in w
template <typename F>
size_t for_each_in(const std::vector<double>& t, const std::vector<double>& v, Window w, F f) {
  size_t n = 0;
  for (size_t i = 0; i < t.size() && i < v.size(); ++i) {
    if (w.contains(t[i]) && std::isfinite(v[i])) {
      f(v[i]);
      ++n;
    }
  }
  return n;
}

}  // namespace

std::vector<double> relative(const std::vector<double>& t_s, double t0_s) {
  std::vector<double> out(t_s);
  for (double& t : out) t -= t0_s;
  return out;
}

std::vector<double> interpolate(const std::vector<double>& t, const std::vector<double>& v,
                                const std::vector<double>& at) {
  std::vector<double> out(at.size(), kNaN);
  if (t.empty()) return out;
  for (size_t k = 0; k < at.size(); ++k) {
    const double x = at[k];
    if (x < t.front() || x > t.back()) continue;
    // first sample later than x; the interval is [hi - 1, hi]
    const auto hi = static_cast<size_t>(std::upper_bound(t.begin(), t.end(), x) - t.begin());
    if (hi == t.size()) {
      out[k] = v.back();
      continue;
    }
    const size_t lo = hi - 1;
    const double span = t[hi] - t[lo];
    out[k] = v[lo] + (v[hi] - v[lo]) * (x - t[lo]) / span;
  }
  return out;
}

std::vector<double> norm(const Axes& a) {
  std::vector<double> out(a[0].size());
  for (size_t i = 0; i < out.size(); ++i) out[i] = std::sqrt(a[0][i] * a[0][i] + a[1][i] * a[1][i] + a[2][i] * a[2][i]);
  return out;
}

std::vector<double> distance(const Axes& a, const Axes& b) {
  Axes d;
  for (size_t axis = 0; axis < 3; ++axis) {
    d[axis].resize(a[axis].size());
    for (size_t i = 0; i < a[axis].size(); ++i) d[axis][i] = a[axis][i] - b[axis][i];
  }
  return norm(d);
}

double mean_in(const std::vector<double>& t, const std::vector<double>& v, Window w) {
  double sum = 0;
  const size_t n = for_each_in(t, v, w, [&](double x) { sum += x; });
  return n == 0 ? kNaN : sum / static_cast<double>(n);
}

double rms_in(const std::vector<double>& t, const std::vector<double>& v, Window w) {
  double sum = 0;
  const size_t n = for_each_in(t, v, w, [&](double x) { sum += x * x; });
  return n == 0 ? kNaN : std::sqrt(sum / static_cast<double>(n));
}

double peak_to_peak_in(const std::vector<double>& t, const std::vector<double>& v, Window w) {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -lo;
  const size_t n = for_each_in(t, v, w, [&](double x) {
    lo = std::min(lo, x);
    hi = std::max(hi, x);
  });
  return n == 0 ? kNaN : hi - lo;
}

std::vector<double> deviation_from_running_mean(const std::vector<double>& x, size_t window) {
  std::vector<double> out(x.size(), kNaN);
  if (window == 0 || x.size() < window) return out;
  const size_t before = window / 2;
  // each window summed on its own, so a NaN sample spoils only the windows that hold it
  for (size_t first = 0; first + window <= x.size(); ++first) {
    double sum = 0;
    for (size_t j = first; j < first + window; ++j) sum += x[j];
    const size_t i = first + before;
    out[i] = std::abs(x[i] - sum / static_cast<double>(window));
  }
  return out;
}

double mean_absolute_deviation_in(const std::vector<double>& t, const std::vector<double>& x, size_t window, Window w) {
  return mean_in(t, deviation_from_running_mean(x, window), w);
}

double fraction_at_least(const std::vector<double>& v, double threshold) {
  if (v.empty()) return kNaN;
  const auto n = std::count_if(v.begin(), v.end(), [&](double x) { return x >= threshold; });
  return static_cast<double>(n) / static_cast<double>(v.size());
}

double fraction_equal(const std::vector<double>& v, double value) {
  if (v.empty()) return kNaN;
  const auto n = std::count(v.begin(), v.end(), value);
  return static_cast<double>(n) / static_cast<double>(v.size());
}

double min_finite(const std::vector<double>& v) {
  double lo = std::numeric_limits<double>::infinity();
  for (double x : v) {
    if (std::isfinite(x)) lo = std::min(lo, x);
  }
  return std::isinf(lo) ? kNaN : lo;
}

double rmse(std::span<const double> errors) {
  if (errors.empty()) return kNaN;
  double sum = 0.0;
  for (const double e : errors) sum += e * e;
  return std::sqrt(sum / static_cast<double>(errors.size()));
}

double max_abs(std::span<const double> errors) {
  if (errors.empty()) return kNaN;
  double out = 0.0;
  for (const double e : errors) out = std::max(out, std::abs(e));
  return out;
}

double rotation_distance(const Quaternion& q1, const Quaternion& q2) {
  // for unit quaternions 1 - (q1 . q2)^2 = |q1|^2 |q2|^2 - (q1 . q2)^2, which Lagrange's identity
  // writes as a sum of squares: 0 for equal (or opposite) quaternions exactly, where 1 - dot^2
  // would leave the rounding of dot, which the square root turns into ~6e-8
  double cross_sq = 0.0;
  for (size_t i = 0; i < 4; ++i) {
    for (size_t j = i + 1; j < 4; ++j) {
      const double c = q1[i] * q2[j] - q1[j] * q2[i];
      cross_sq += c * c;
    }
  }
  return 2.0 * std::sqrt(2.0 * cross_sq);
}

Summary summarize_in(const std::vector<double>& t, const std::vector<double>& v, Window w) {
  double sum = 0.0;
  double hi = -std::numeric_limits<double>::infinity();
  const size_t n = for_each_in(t, v, w, [&](double x) {
    sum += x;
    hi = std::max(hi, x);
  });
  if (n == 0) return {kNaN, kNaN, kNaN, 0};
  const double mean = sum / static_cast<double>(n);
  // two passes: no cancellation when the spread is small against the mean
  double sum_sq = 0.0;
  for_each_in(t, v, w, [&](double x) { sum_sq += (x - mean) * (x - mean); });
  return {mean, std::sqrt(sum_sq / static_cast<double>(n)), hi, n};
}

}  // namespace teleop::experiment
