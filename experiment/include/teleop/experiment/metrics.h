#pragma once
// Small pure functions over sampled signals, the building blocks of the experiment analysis.
// Samples are (t, v) with t ascending; NaN values are skipped where a mean or extreme is taken.

#include <array>
#include <cstddef>
#include <span>
#include <vector>

namespace teleop::experiment {

/// A closed time interval [begin_s, end_s].
struct Window {
  double begin_s;
  double end_s;
  bool contains(double t_s) const { return t_s >= begin_s && t_s <= end_s; }
};

/// Three components of a vector signal (x, y, z), each one sample per time.
using Axes = std::array<std::vector<double>, 3>;

/// `v(t)` linearly interpolated at each time in `at`; NaN outside [t.front(), t.back()] (no
/// extrapolation). `t` ascending; equal times keep the later sample.
std::vector<double> interpolate(const std::vector<double>& t, const std::vector<double>& v,
                                const std::vector<double>& at);

/// The times `t_s` taken relative to `t0_s`.
std::vector<double> relative(const std::vector<double>& t_s, double t0_s);

/// Per sample: the Euclidean norm |a|.
std::vector<double> norm(const Axes& a);
/// Per sample: the Euclidean distance |a - b|.
std::vector<double> distance(const Axes& a, const Axes& b);

/// Mean of the finite values whose time lies in `w`; NaN when there are none.
double mean_in(const std::vector<double>& t, const std::vector<double>& v, Window w);
/// Root mean square of the finite values whose time lies in `w`; NaN when there are none.
double rms_in(const std::vector<double>& t, const std::vector<double>& v, Window w);
/// max - min of the finite values whose time lies in `w`; NaN when there are none.
double peak_to_peak_in(const std::vector<double>& t, const std::vector<double>& v, Window w);

/// |x_i - x̄_i| per sample, x̄_i the mean of the `window` samples centred on i (i - window/2 to
/// i + (window - 1)/2); NaN where that window does not fit in the signal.
std::vector<double> deviation_from_running_mean(const std::vector<double>& x, size_t window);
/// The Mean Absolute Deviation of `x` from its running mean over `window` samples,
/// MAD = Σ|x_i - x̄_i| / N, over the N samples whose time lies in `w`.
double mean_absolute_deviation_in(const std::vector<double>& t, const std::vector<double>& x, size_t window, Window w);

/// Fraction of all samples (NaN included in the count) with v >= threshold; NaN when empty.
double fraction_at_least(const std::vector<double>& v, double threshold);
/// Fraction of all samples equal to `value`; NaN when empty.
double fraction_equal(const std::vector<double>& v, double value);
/// Smallest finite value; NaN when there is none.
double min_finite(const std::vector<double>& v);

// --- simulation fidelity (the coupling thesis, §4.1: real robot against its simulation) ---

/// Root mean square of the errors, thesis eq. 4.2: sqrt(sum e_i^2 / N). In the unit of the
/// errors (degrees in, "degrees" out): N equal errors of size y give y. NaN when empty.
double rmse(std::span<const double> errors);
/// Largest |e_i|; NaN when empty.
double max_abs(std::span<const double> errors);

/// A rotation as a unit quaternion (w, x, y, z).
using Quaternion = std::array<double, 4>;
/// The rotation distance of thesis eq. 4.5, theta = 2 sqrt(2 (1 - (q1 . q2)^2)), the dot
/// product over all four components. Dimensionless, 0 for equal rotations, the same for q and
/// -q (the same rotation), 2 sqrt(2) sin(alpha / 2) for two rotations alpha apart: 0.0247 for
/// 1 degree, 2 for 90 degrees. Both quaternions must be unit (1 - (q1 . q2)^2 is computed as
/// |q1|^2 |q2|^2 - (q1 . q2)^2, by Lagrange's identity, so equal rotations give exactly 0).
double rotation_distance(const Quaternion& q1, const Quaternion& q2);

/// Mean, standard deviation (population) and maximum of a signal over time: what the thesis
/// keeps of each movement's error signal (§4.2.3).
struct Summary {
  double mean = 0.0;
  double sd = 0.0;
  double max = 0.0;
  size_t samples = 0;
};
/// Summary of the finite values whose time lies in `w`; NaN fields (and 0 samples) when none.
Summary summarize_in(const std::vector<double>& t, const std::vector<double>& v, Window w);

}  // namespace teleop::experiment
