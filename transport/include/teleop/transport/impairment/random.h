#pragma once
// Deterministic random numbers for the impairment model: the same seed gives the same draws on
// every platform (no dependence on the standard library's distributions).

#include <cstdint>

namespace teleop::transport::impairment {

/// SplitMix64: small, fast, statistically sound for simulation, fully specified.
class Rng {
 public:
  explicit Rng(uint64_t seed) : state_(seed) {}

  uint64_t next() {
    uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }

  /// Uniform in [0, 1) with 53 random bits.
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

 private:
  uint64_t state_;
};

/// netem's correlated uniform: u_n = (1 - c) * rand + c * u_(n-1).
class CorrelatedUniform {
 public:
  double next(Rng& rng, double correlation) {
    const double fresh = rng.uniform();
    last_ = correlation > 0 ? (1.0 - correlation) * fresh + correlation * last_ : fresh;
    return last_;
  }

 private:
  double last_ = 0.5;
};

/// Inverse of the standard normal CDF (Acklam's rational approximation, |rel. error| < 1.2e-9).
double inverse_normal_cdf(double p);

/// Standard-score of a draw from a Pareto distribution with shape 3 (mean 0, variance 1):
/// netem's heavy-tailed jitter, by inverse CDF of `u`.
double standard_pareto(double u);

/// 64-bit FNV-1a of a string: derives independent per-link seeds from one run seed.
uint64_t hash_name(const char* name);

}  // namespace teleop::transport::impairment
