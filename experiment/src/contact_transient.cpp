// How the contact was made: a run that is stable in its hold window may still hit the wall hard,
// overshoot and take seconds to settle (a sluggish or bouncy architecture), which the hold
// metrics alone hide.
#include <cmath>
#include <limits>

#include "teleop/experiment/analysis.h"

namespace teleop::experiment {

void analyse_contact_transient(const std::vector<double>& t_rel_s, const std::vector<double>& force_n, Window hold,
                               RunMetrics& m) {
  const double held_n = mean_in(t_rel_s, force_n, hold);
  if (!(held_n >= kContactForceN)) return;  // no contact held: nothing to settle on
  double peak_n = 0;
  for (size_t i = 0; i < force_n.size() && t_rel_s[i] <= hold.end_s; ++i) {
    if (t_rel_s[i] >= 0 && std::isfinite(force_n[i])) peak_n = std::fmax(peak_n, force_n[i]);
  }
  m.impact_peak_n = peak_n;
  m.overshoot_fraction = peak_n / held_n - 1.0;
  // settled from the sample after the last one outside the band, if that is still in the window
  const double band_n = kSettleBand * held_n;
  size_t in_band_from = 0;
  size_t end = 0;
  for (; end < force_n.size() && t_rel_s[end] <= hold.end_s; ++end) {
    if (t_rel_s[end] >= 0 && !(std::fabs(force_n[end] - held_n) <= band_n)) in_band_from = end + 1;
  }
  m.settle_time_s = in_band_from < end ? std::fmax(0.0, t_rel_s[in_band_from]) : std::numeric_limits<double>::infinity();
}

}  // namespace teleop::experiment
