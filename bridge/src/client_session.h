#pragma once
// One connected client: its subscriptions (each channel at most once, each thinned by its own rate
// limiter) and the bounded queue of frames waiting for its socket. Offered samples come from Fast
// DDS threads, subscriptions and sends from the server's thread.

#include <atomic>
#include <cstdint>
#include <map>
#include <mutex>
#include <optional>
#include <string>

#include "rate_limiter.h"
#include "send_queue.h"

namespace teleop::bridge {

struct ClientStats {
  uint64_t sent = 0;
  /// Dropped from the full send queue (the client did not keep up).
  uint64_t dropped = 0;
  /// Held back by the rate limit.
  uint64_t limited = 0;
};

class ClientSession {
 public:
  ClientSession(std::string remote, double max_rate_hz, size_t queue_capacity);

  /// Subscribes `subscription_id` to `channel_id`; an error message when the id is taken or the
  /// channel already subscribed.
  std::optional<std::string> subscribe(uint32_t subscription_id, uint32_t channel_id);
  /// An error message when the id is not subscribed.
  std::optional<std::string> unsubscribe(uint32_t subscription_id);

  /// A message of `channel_id` (`size` bytes, received at `receive_ns`, CLOCK_REALTIME) offered at
  /// `now_ns` (monotonic): queued as a message frame when subscribed and the rate limit lets it
  /// pass. Returns whether the sender should be woken.
  bool offer(uint32_t channel_id, const uint8_t* payload, size_t size, int64_t receive_ns, int64_t now_ns);

  SendQueue& queue() { return queue_; }
  void count_sent() { sent_.fetch_add(1, std::memory_order_relaxed); }
  ClientStats stats() const;
  const std::string& remote() const { return remote_; }

 private:
  struct Subscription {
    uint32_t id;
    RateLimiter limiter;
  };

  const std::string remote_;
  const double max_rate_hz_;
  mutable std::mutex mutex_;
  std::map<uint32_t, Subscription> by_channel_;
  uint64_t limited_ = 0;
  std::atomic<uint64_t> sent_{0};
  SendQueue queue_;
};

}  // namespace teleop::bridge
