#pragma once
// First-order IIR low-pass filter, y += alpha (x - y), on fixed-size vectors.

#include <cmath>
#include <cstddef>

#include "teleop/common/joint_model.h"

namespace teleop {

class LowPassFilter {
 public:
  /// cutoff_hz <= 0 or >= the Nyquist rate disables filtering (alpha = 1).
  LowPassFilter(double cutoff_hz, double sample_rate_hz) {
    if (cutoff_hz > 0 && cutoff_hz < sample_rate_hz / 2) {
      const double rc = 1.0 / (2.0 * M_PI * cutoff_hz);
      const double dt = 1.0 / sample_rate_hz;
      alpha_ = dt / (rc + dt);
    }
  }

  /// Filters `x` in place into the state and returns the state. Real-time safe.
  const JointVector& apply(const JointVector& x, size_t n) {
    for (size_t i = 0; i < n; ++i) y_[i] += alpha_ * (x[i] - y_[i]);
    return y_;
  }

  double alpha() const { return alpha_; }

 private:
  double alpha_ = 1.0;
  JointVector y_{};
};

}  // namespace teleop
