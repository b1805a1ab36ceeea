#include "client_session.h"

#include <algorithm>

#include "foxglove_protocol.h"

namespace teleop::bridge {

ClientSession::ClientSession(std::string remote, double max_rate_hz, size_t queue_capacity)
    : remote_(std::move(remote)), max_rate_hz_(max_rate_hz), queue_(queue_capacity) {}

std::optional<std::string> ClientSession::subscribe(uint32_t subscription_id, uint32_t channel_id) {
  std::lock_guard lock(mutex_);
  if (by_channel_.count(channel_id) > 0) return "channel " + std::to_string(channel_id) + " is already subscribed";
  const bool id_taken = std::any_of(by_channel_.begin(), by_channel_.end(),
                                    [&](const auto& entry) { return entry.second.id == subscription_id; });
  if (id_taken) return "subscription id " + std::to_string(subscription_id) + " is in use";
  by_channel_.emplace(channel_id, Subscription{subscription_id, RateLimiter(max_rate_hz_)});
  return std::nullopt;
}

std::optional<std::string> ClientSession::unsubscribe(uint32_t subscription_id) {
  std::lock_guard lock(mutex_);
  const auto it = std::find_if(by_channel_.begin(), by_channel_.end(),
                               [&](const auto& entry) { return entry.second.id == subscription_id; });
  if (it == by_channel_.end()) return "no subscription " + std::to_string(subscription_id);
  by_channel_.erase(it);
  return std::nullopt;
}

bool ClientSession::offer(uint32_t channel_id, const uint8_t* payload, size_t size, int64_t receive_ns,
                          int64_t now_ns) {
  uint32_t subscription_id = 0;
  {
    std::lock_guard lock(mutex_);
    const auto it = by_channel_.find(channel_id);
    if (it == by_channel_.end()) return false;
    if (!it->second.limiter.admit(now_ns)) {
      ++limited_;
      return false;
    }
    subscription_id = it->second.id;
  }
  return queue_.push(message_data_frame(subscription_id, static_cast<uint64_t>(receive_ns), payload, size));
}

ClientStats ClientSession::stats() const {
  std::lock_guard lock(mutex_);
  return {sent_.load(std::memory_order_relaxed), queue_.dropped(), limited_};
}

}  // namespace teleop::bridge
