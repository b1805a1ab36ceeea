#pragma once
// What waits to go to one client: bounded, and when full the oldest frame makes room (a live
// view wants the newest data, and a stalled client must not grow the bridge's memory). Frames
// are pushed on Fast DDS threads and taken on the server's thread, so a slow client costs the
// bus a short lock, never a wait on the network.

#include <cstddef>
#include <cstdint>
#include <deque>
#include <mutex>
#include <optional>
#include <string>

namespace teleop::bridge {

class SendQueue {
 public:
  explicit SendQueue(size_t capacity);

  /// Appends `frame`, dropping the oldest when full. Returns whether the queue was empty before
  /// (the caller then wakes the sender).
  bool push(std::string frame);
  /// The oldest frame, if any.
  std::optional<std::string> pop();

  size_t size() const;
  /// Frames dropped to make room since the start.
  uint64_t dropped() const;

 private:
  const size_t capacity_;
  mutable std::mutex mutex_;
  std::deque<std::string> frames_;
  uint64_t dropped_ = 0;
};

}  // namespace teleop::bridge
