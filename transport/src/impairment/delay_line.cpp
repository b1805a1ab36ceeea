#include "teleop/transport/impairment/delay_line.h"

#include <sys/prctl.h>

#include <algorithm>
#include <chrono>
#include <cstring>

#include "teleop/common/clock.h"

namespace teleop::transport::impairment {
namespace rtps = eprosima::fastrtps::rtps;

namespace {

// iterates over exactly one locator (Fast DDS's interface has no virtual destructor; this type is
// only ever used by value)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnon-virtual-dtor"
struct OneLocator final : eprosima::fastdds::rtps::LocatorsIterator {
  const rtps::Locator_t* locator;
  bool at_end;
  OneLocator(const rtps::Locator_t* l, bool end) : locator(l), at_end(end) {}
  LocatorsIterator& operator++() override {
    at_end = true;
    return *this;
  }
  bool operator==(const LocatorsIterator& other) const override {
    return at_end == static_cast<const OneLocator&>(other).at_end;
  }
  bool operator!=(const LocatorsIterator& other) const override { return !(*this == other); }
  const rtps::Locator_t& operator*() const override { return *locator; }
};
#pragma GCC diagnostic pop

// tells the core we are spinning (saves power, yields to a hyper-thread sibling)
inline void cpu_relax() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#elif defined(__aarch64__)
  asm volatile("yield");
#endif
}

}  // namespace

bool send_to_one(rtps::SenderResource* sender, const uint8_t* data, uint32_t size, const rtps::Locator_t& destination) {
  OneLocator begin(&destination, false);
  OneLocator end(&destination, true);
  // a datagram send does not block; the deadline only bounds a full socket buffer
  const auto timeout = std::chrono::steady_clock::now() + std::chrono::milliseconds(1);
  return sender->send(data, size, &begin, &end, timeout);
}

DelayLine::DelayLine(size_t slots, size_t slot_bytes)
    : slot_bytes_(slot_bytes), slots_(slots), storage_(slots * slot_bytes) {
  free_.reserve(slots);
  heap_.reserve(slots);
  for (size_t i = slots; i > 0; --i) free_.push_back(static_cast<uint32_t>(i - 1));
  thread_ = std::thread([this] { run(); });
}

DelayLine::~DelayLine() { stop(); }

bool DelayLine::earlier(uint32_t a, uint32_t b) const {
  const Slot& x = slots_[a];
  const Slot& y = slots_[b];
  return x.due_ns != y.due_ns ? x.due_ns < y.due_ns : x.order < y.order;
}

void DelayLine::heap_push(uint32_t slot) {
  heap_.push_back(slot);  // within the reserved capacity: no allocation
  std::push_heap(heap_.begin(), heap_.end(), [this](uint32_t a, uint32_t b) { return earlier(b, a); });
}

uint32_t DelayLine::heap_pop() {
  std::pop_heap(heap_.begin(), heap_.end(), [this](uint32_t a, uint32_t b) { return earlier(b, a); });
  const uint32_t slot = heap_.back();
  heap_.pop_back();
  return slot;
}

bool DelayLine::push(int64_t due_ns, rtps::SenderResource* sender, const rtps::Locator_t& destination,
                     const uint8_t* data, uint32_t size) {
  std::lock_guard lock(mutex_);
  if (!running_ || free_.empty() || size > slot_bytes_) {
    ++dropped_full_;
    return false;
  }
  const uint32_t slot = free_.back();
  free_.pop_back();
  slots_[slot] = Slot{due_ns, next_order_++, sender, destination, size};
  std::memcpy(storage_.data() + slot * slot_bytes_, data, size);
  heap_push(slot);
  // wake the thread only when this message is due before whatever it is waiting for
  if (heap_.front() == slot) wake_.notify_one();
  return true;
}

void DelayLine::run() {
  // wake up at the due time, not up to 50 us later
  prctl(PR_SET_TIMERSLACK, 1UL, 0UL, 0UL, 0UL);
  std::unique_lock lock(mutex_);
  while (running_) {
    if (heap_.empty()) {
      wake_.wait(lock);
      continue;
    }
    const int64_t due = slots_[heap_.front()].due_ns;
    int64_t now = monotonic_now_ns();
    const int64_t wake_at = due - wake_early_ns_;
    if (now < wake_at) {
      wake_.wait_until(lock, std::chrono::steady_clock::time_point(std::chrono::nanoseconds(wake_at)));
      const int64_t woke = monotonic_now_ns();
      if (woke >= wake_at && !heap_.empty() && slots_[heap_.front()].due_ns == due) {
        // learn the timer's wake-up lateness (EWMA, 1/8) and wake that much (plus margin) early
        const int64_t lateness = woke - wake_at;
        const int64_t target = std::clamp(lateness + kMinWakeEarlyNs, kMinWakeEarlyNs, kMaxWakeEarlyNs);
        wake_early_ns_ += (target - wake_early_ns_) / 8;
      }
      continue;
    }
    if (now < due) {
      // the last few microseconds: spin without the lock, so pushes are not held up
      lock.unlock();
      while ((now = monotonic_now_ns()) < due) cpu_relax();
      lock.lock();
      continue;
    }
    const uint32_t slot = heap_pop();
    const Slot s = slots_[slot];
    max_lateness_ns_ = std::max(max_lateness_ns_, now - due);
    lock.unlock();
    send_to_one(s.sender, storage_.data() + slot * slot_bytes_, s.size, s.destination);
    lock.lock();
    ++sent_;
    free_.push_back(slot);
  }
}

void DelayLine::stop() {
  {
    std::lock_guard lock(mutex_);
    if (!running_) return;
    running_ = false;
    dropped_at_stop_ += heap_.size();
    heap_.clear();
  }
  wake_.notify_one();
  if (thread_.joinable()) thread_.join();
}

uint64_t DelayLine::sent() const {
  std::lock_guard lock(mutex_);
  return sent_;
}

uint64_t DelayLine::dropped_full() const {
  std::lock_guard lock(mutex_);
  return dropped_full_;
}

uint64_t DelayLine::dropped_at_stop() const {
  std::lock_guard lock(mutex_);
  return dropped_at_stop_;
}

int64_t DelayLine::max_lateness_ns() const {
  std::lock_guard lock(mutex_);
  return max_lateness_ns_;
}

}  // namespace teleop::transport::impairment
