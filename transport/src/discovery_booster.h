#pragma once
// Endpoint discovery that survives a lossy link: Fast DDS 2.9 repairs a lost endpoint
// announcement (SEDP) on a fixed one-second heartbeat its API does not let us shorten, so over the
// soak's 50 % bursty loss a restarted node was matched again only after 2-4 s (up to 19 s). When a
// new participant appears, this re-announces every endpoint of ours a few times in quick
// succession (a change of the endpoint's user data makes Fast DDS send its announcement afresh,
// as a new sample with its own sequence number), so that one of the copies gets through within
// a fraction of a second. Both sides do it, each for its own endpoints.

#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <thread>

namespace teleop::transport {

struct DiscoveryBoost {
  /// How long after a new participant appeared, and how often, the endpoints are re-announced;
  /// a duration of 0: never.
  int64_t duration_ns = 2'000'000'000;
  int64_t period_ns = 100'000'000;
};

class DiscoveryBooster {
 public:
  DiscoveryBooster(eprosima::fastdds::dds::Publisher& publisher, eprosima::fastdds::dds::Subscriber& subscriber,
                   DiscoveryBoost boost);
  ~DiscoveryBooster();
  DiscoveryBooster(const DiscoveryBooster&) = delete;
  DiscoveryBooster& operator=(const DiscoveryBooster&) = delete;

  /// A new participant appeared (any thread, e.g. Fast DDS's discovery listener). Ignored until
  /// armed: Fast DDS 2.9 asserts when an endpoint is re-announced while it is still being created.
  void kick();
  /// Every endpoint exists and no more will be made: kicks from now on re-announce, this one too.
  void arm_and_kick();
  /// Re-announcements sent so far (one per endpoint each time).
  uint64_t announcements() const { return announcements_.load(std::memory_order_relaxed); }

 private:
  void run();
  void reannounce();

  eprosima::fastdds::dds::Publisher& publisher_;
  eprosima::fastdds::dds::Subscriber& subscriber_;
  DiscoveryBoost boost_;
  std::mutex mutex_;
  std::condition_variable wake_;
  int64_t boost_until_ns_ = 0;  // under mutex_
  bool armed_ = false;          // under mutex_
  bool stop_ = false;           // under mutex_
  uint32_t generation_ = 0;
  std::atomic<uint64_t> announcements_{0};
  std::thread thread_;
};

}  // namespace teleop::transport
