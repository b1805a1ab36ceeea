#pragma once
// What an impaired link does to the messages sent over it, one direction: netem-class delay,
// jitter, loss, duplication, reordering, rate limit and outages, possibly changing over time.

#include <cstdint>
#include <string>
#include <vector>

#include "teleop/common/config.h"

namespace teleop::transport::impairment {

enum class DelayDistribution { kConstant, kUniform, kNormal, kPareto };

enum class LossModel { kNone, kBernoulli, kGilbertElliott };

struct LossSpec {
  LossModel model = LossModel::kNone;
  /// Bernoulli: probability that a message is lost.
  double probability = 0.0;
  /// Gilbert-Elliott (netem's gemodel p, r, 1-h, 1-k): good->bad and bad->good transition
  /// probabilities per message, and the loss probability in each state.
  double p = 0.0;
  double r = 1.0;
  double loss_in_bad = 1.0;   ///< 1-h
  double loss_in_good = 0.0;  ///< 1-k

  /// Long-run loss rate of the model.
  double expected_loss_rate() const;
  /// Gilbert-Elliott: mean number of consecutive messages in the bad state (1/r).
  double expected_bad_run_length() const { return r > 0 ? 1.0 / r : 0.0; }
};

/// One phase of a link: constant settings for `duration_ns` (the last phase lasts forever).
struct LinkPhase {
  int64_t duration_ns = 0;
  int64_t delay_ns = 0;
  /// Spread of the delay: half-width for uniform, standard deviation for normal and pareto.
  int64_t jitter_ns = 0;
  DelayDistribution distribution = DelayDistribution::kConstant;
  /// Correlation (0..1) of successive delay draws, as netem: u_n = (1-c) rand + c u_(n-1).
  double correlation = 0.0;
  LossSpec loss;
  double duplicate_probability = 0.0;
  /// Messages sent at once, skipping the delay (and so overtaking queued ones), with this
  /// probability, considering every `reorder_gap`-th message. 0: order is always kept.
  double reorder_probability = 0.0;
  uint32_t reorder_gap = 1;
  /// Serialisation rate in bit/s (0: unlimited) and the queue in front of it [messages].
  double rate_bps = 0.0;
  uint32_t queue_limit = 1000;
  /// The link is down (every message lost) for the whole phase.
  bool down = false;
};

/// A named, possibly time-varying profile: phases in order, plus outage windows.
struct LinkProfile {
  std::string name = "none";
  std::vector<LinkPhase> phases{LinkPhase{}};
  struct Outage {
    int64_t start_ns;
    int64_t duration_ns;
  };
  /// Windows (from the link's start) in which every message is lost.
  std::vector<Outage> outages;

  /// True when the profile does nothing to any message (zero delay, no loss, ...).
  bool is_transparent() const;
};

/// Reads a profile from a mapping (the keys documented in config/network/README.md).
/// Throws ConfigError naming file and key.
LinkProfile parse_link_profile(const ConfigNode& node);
/// Reads a profile file (top-level key `profile`).
LinkProfile load_link_profile(const std::string& path);

}  // namespace teleop::transport::impairment
