#pragma once
// Decides, message by message, what an impaired link does: drop, duplicate, or deliver after a
// delay. Deterministic: the same seed and the same sequence of (time, size) give the same
// decisions. Pure logic on a caller-provided clock, so it is tested without DDS or real time.

#include <array>
#include <cstdint>

#include "teleop/common/histogram.h"
#include "teleop/transport/impairment/link_profile.h"
#include "teleop/transport/impairment/random.h"

namespace teleop::transport::impairment {

enum class DropReason : uint8_t { kNone, kLoss, kOutage, kQueue };

const char* to_string(DropReason reason);

/// What happens to one message.
struct Decision {
  DropReason drop = DropReason::kNone;
  /// 1, or 2 when duplicated; 0 when dropped.
  int copies = 0;
  /// Absolute delivery times of the copies, on the caller's clock.
  std::array<int64_t, 2> deliver_at_ns{};
  /// Sent ahead of messages still queued (reordering on purpose).
  bool reordered = false;
};

/// Counters of one link.
struct LinkStats {
  uint64_t messages = 0;    ///< offered to the link
  uint64_t delivered = 0;   ///< copies scheduled for delivery (duplicates included)
  uint64_t lost = 0;        ///< dropped by the loss model
  uint64_t outage = 0;      ///< dropped because the link was down
  uint64_t queue = 0;       ///< dropped because the rate limiter's queue was full
  uint64_t duplicated = 0;
  uint64_t reordered = 0;
  /// Lengths of runs of consecutive dropped messages.
  DurationHistogram loss_runs;
  /// Delay added to delivered messages [ns].
  DurationHistogram delay;

  uint64_t dropped() const { return lost + outage + queue; }
};

class LinkModel {
 public:
  /// `start_ns` is when the link comes up: phases and outages count from it.
  LinkModel(const LinkProfile& profile, uint64_t seed, int64_t start_ns);

  /// Decides for a message of `bytes` sent at `now_ns` (non-decreasing). Real-time safe.
  Decision decide(int64_t now_ns, uint32_t bytes);

  const LinkStats& stats() const { return stats_; }
  const LinkProfile& profile() const { return profile_; }

 private:
  const LinkPhase& phase_at(int64_t elapsed_ns);
  bool in_outage(int64_t elapsed_ns) const;
  bool lose(const LossSpec& loss);
  int64_t draw_delay(const LinkPhase& phase);
  bool rate_limit(const LinkPhase& phase, int64_t now_ns, uint32_t bytes, int64_t& ready_ns);
  void record(const Decision& d, int64_t now_ns);

  LinkProfile profile_;
  Rng rng_;
  CorrelatedUniform delay_uniform_;
  int64_t start_ns_;
  size_t phase_index_ = 0;
  int64_t phase_end_ns_;
  bool ge_bad_ = false;
  uint64_t reorder_counter_ = 0;
  int64_t last_delivery_ns_ = 0;
  // rate limiter: when the link finishes serialising what is queued, and a ring of finish
  // times of the messages still queued (bounded by the queue limit)
  int64_t link_free_ns_ = 0;
  static constexpr size_t kMaxQueue = 4096;
  std::array<int64_t, kMaxQueue> queue_finish_ns_{};
  size_t queue_head_ = 0;
  size_t queue_size_ = 0;
  uint64_t current_loss_run_ = 0;
  LinkStats stats_;
};

}  // namespace teleop::transport::impairment
