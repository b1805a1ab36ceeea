#include "teleop/transport/impairment/random.h"

#include <algorithm>
#include <cmath>

namespace teleop::transport::impairment {

double inverse_normal_cdf(double p) {
  // coefficients of P. J. Acklam's algorithm
  static constexpr double a[] = {-3.969683028665376e+01, 2.209460984245205e+02, -2.759285104469687e+02,
                                 1.383577518672690e+02,  -3.066479806614716e+01, 2.506628277459239e+00};
  static constexpr double b[] = {-5.447609879822406e+01, 1.615858368580409e+02, -1.556989798598866e+02,
                                 6.680131188771972e+01,  -1.328068155288572e+01};
  static constexpr double c[] = {-7.784894002430293e-03, -3.223964580411365e-01, -2.400758277161838e+00,
                                 -2.549732539343734e+00, 4.374664141464968e+00,  2.938163982698783e+00};
  static constexpr double d[] = {7.784695709041462e-03, 3.224671290700398e-01, 2.445134137142996e+00,
                                 3.754408661907416e+00};
  constexpr double kLow = 0.02425;
  const double q0 = std::clamp(p, 1e-300, 1.0 - 1e-16);
  if (q0 < kLow) {
    const double q = std::sqrt(-2 * std::log(q0));
    return (((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
           ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1);
  }
  if (q0 > 1 - kLow) {
    const double q = std::sqrt(-2 * std::log(1 - q0));
    return -(((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
           ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1);
  }
  const double q = q0 - 0.5;
  const double r = q * q;
  return (((((a[0] * r + a[1]) * r + a[2]) * r + a[3]) * r + a[4]) * r + a[5]) * q /
         (((((b[0] * r + b[1]) * r + b[2]) * r + b[3]) * r + b[4]) * r + 1);
}

double standard_pareto(double u) {
  // X = (1 - u)^(-1/3) has mean 3/2 and variance 3/4 for shape 3 and scale 1
  constexpr double kShape = 3.0;
  constexpr double kMean = 1.5;
  static const double kStdDev = std::sqrt(0.75);
  const double x = std::pow(1.0 - std::min(u, 1.0 - 1e-16), -1.0 / kShape);
  return (x - kMean) / kStdDev;
}

uint64_t hash_name(const char* name) {
  uint64_t h = 0xcbf29ce484222325ull;
  for (const char* c = name; *c != '\0'; ++c) {
    h ^= static_cast<unsigned char>(*c);
    h *= 0x100000001b3ull;
  }
  return h;
}

}  // namespace teleop::transport::impairment
