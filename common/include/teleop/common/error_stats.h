#pragma once
// Running root-mean-square and maximum of an error signal (tracking metrics, thesis §4.1).
// Real-time safe: two sums and a max.

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace teleop {

class ErrorStats {
 public:
  void add(double error) {
    sum_sq_ += error * error;
    max_abs_ = std::max(max_abs_, std::abs(error));
    ++count_;
  }
  uint64_t count() const { return count_; }
  /// 0 when nothing was added.
  double rms() const { return count_ > 0 ? std::sqrt(sum_sq_ / static_cast<double>(count_)) : 0.0; }
  double max_abs() const { return max_abs_; }

 private:
  double sum_sq_ = 0.0;
  double max_abs_ = 0.0;
  uint64_t count_ = 0;
};

}  // namespace teleop
