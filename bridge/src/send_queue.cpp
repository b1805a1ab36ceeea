#include "send_queue.h"

namespace teleop::bridge {

SendQueue::SendQueue(size_t capacity) : capacity_(capacity > 0 ? capacity : 1) {}

bool SendQueue::push(std::string frame) {
  std::lock_guard lock(mutex_);
  const bool was_empty = frames_.empty();
  if (frames_.size() >= capacity_) {
    frames_.pop_front();
    ++dropped_;
  }
  frames_.push_back(std::move(frame));
  return was_empty;
}

std::optional<std::string> SendQueue::pop() {
  std::lock_guard lock(mutex_);
  if (frames_.empty()) return std::nullopt;
  std::string frame = std::move(frames_.front());
  frames_.pop_front();
  return frame;
}

size_t SendQueue::size() const {
  std::lock_guard lock(mutex_);
  return frames_.size();
}

uint64_t SendQueue::dropped() const {
  std::lock_guard lock(mutex_);
  return dropped_;
}

}  // namespace teleop::bridge
