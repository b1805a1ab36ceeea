#include "environment_correction.h"

#include <algorithm>
#include <cmath>

namespace teleop::twin {

EnvironmentCorrection::Outcome EnvironmentCorrection::measure(const SurfaceMeasurement& m) {
  if (!std::isfinite(m.gap_m) || !std::isfinite(m.normal_force_n) || !std::isfinite(m.age_s)) {
    ++non_finite_;
    return Outcome::kNonFinite;
  }
  if (m.age_s > config_.timeout_s) {
    ++stale_;
    return Outcome::kStale;
  }
  // the probe's position is absolute (the gap was taken against the surface at applied_m_), so an
  // old measurement of a static surface is as good as a new one: no need for the twin's past state
  const double probe_m = applied_m_ + m.gap_m;
  if (m.normal_force_n >= config_.contact_force_n) {
    // touching the real surface: it is where the probe is
    ++contact_updates_;
    set_estimate(probe_m);
    return Outcome::kContact;
  }
  if (m.normal_force_n < config_.free_force_n && probe_m < estimate_m_ - config_.free_margin_m) {
    // free, clearly behind the estimated surface: the real one is further back than the probe
    ++free_updates_;
    set_estimate(probe_m - config_.free_margin_m);
    return Outcome::kFree;
  }
  return Outcome::kNoChange;
}

double EnvironmentCorrection::advance(double dt_s) {
  const double step = config_.rate_m_per_s * dt_s;
  applied_m_ += std::clamp(estimate_m_ - applied_m_, -step, step);
  return applied_m_;
}

void EnvironmentCorrection::set_estimate(double offset_m) {
  const double bound = config_.max_offset_m;
  if (std::abs(offset_m) > bound) ++clamped_;
  estimate_m_ = std::clamp(offset_m, -bound, bound);
}

}  // namespace teleop::twin
