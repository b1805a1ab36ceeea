#pragma once
// Holds delayed messages and sends each at its due time from a thread of its own, so that no
// Fast DDS thread (nor the control loop writing a sample) ever sleeps for a delay.


// first: Fast DDS headers need LocatorsIterator declared before Locator
#include <fastdds/rtps/transport/TransportInterface.h>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <thread>
#include <vector>

namespace teleop::transport::impairment {

/// Sends a buffer to one locator through a low-level sender resource.
bool send_to_one(eprosima::fastrtps::rtps::SenderResource* sender, const uint8_t* data, uint32_t size,
                 const eprosima::fastrtps::rtps::Locator_t& destination);

class DelayLine {
 public:
  /// `slots` messages of at most `slot_bytes` each can wait at once; memory is allocated here.
  DelayLine(size_t slots, size_t slot_bytes);
  ~DelayLine();
  DelayLine(const DelayLine&) = delete;
  DelayLine& operator=(const DelayLine&) = delete;

  /// Copies the message and sends it at `due_ns` (CLOCK_MONOTONIC). Returns false, and counts
  /// it, when no slot is free or the message is larger than a slot. No allocation.
  bool push(int64_t due_ns, eprosima::fastrtps::rtps::SenderResource* sender,
            const eprosima::fastrtps::rtps::Locator_t& destination, const uint8_t* data, uint32_t size);

  /// Stops the thread; messages still waiting are dropped and counted. Must run before the
  /// sender resources go away (the participant's shutdown). Idempotent.
  void stop();

  uint64_t sent() const;
  uint64_t dropped_full() const;
  uint64_t dropped_at_stop() const;
  /// How late the thread sent messages after their due time.
  int64_t max_lateness_ns() const;

 private:
  struct Slot {
    int64_t due_ns;
    uint64_t order;
    eprosima::fastrtps::rtps::SenderResource* sender;
    eprosima::fastrtps::rtps::Locator_t destination;
    uint32_t size;
  };
  bool earlier(uint32_t a, uint32_t b) const;
  void heap_push(uint32_t slot);
  uint32_t heap_pop();
  void run();

  size_t slot_bytes_;
  std::vector<Slot> slots_;
  std::vector<uint8_t> storage_;
  std::vector<uint32_t> free_;
  std::vector<uint32_t> heap_;
  uint64_t next_order_ = 0;
  bool running_ = true;
  uint64_t sent_ = 0;
  uint64_t dropped_full_ = 0;
  uint64_t dropped_at_stop_ = 0;
  int64_t max_lateness_ns_ = 0;
  // how long before a due time the thread goes to sleep's end: its learnt wake-up lateness
  // plus a margin; the rest it spins, so messages leave on time despite slow timer wake-ups
  int64_t wake_early_ns_ = kMinWakeEarlyNs;
  static constexpr int64_t kMinWakeEarlyNs = 20'000;
  static constexpr int64_t kMaxWakeEarlyNs = 300'000;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::thread thread_;
};

}  // namespace teleop::transport::impairment
