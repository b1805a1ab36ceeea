#pragma once
// The impairment of one participant's outgoing traffic: a LinkModel per peer, decisions per
// destination locator, immediate or delayed sends.


// first: Fast DDS headers need LocatorsIterator declared before Locator
#include <fastdds/rtps/transport/TransportInterface.h>
#include <atomic>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "teleop/transport/impairment/delay_line.h"
#include "teleop/transport/impairment/impairment_config.h"
#include "teleop/transport/impairment/link_model.h"
#include "teleop/transport/impairment/peer_directory.h"

namespace teleop::transport::impairment {

/// What one link did, for status and reports.
struct LinkReport {
  std::string from;
  std::string to;
  std::string profile;
  LinkStats stats;
  double configured_loss;
  int64_t configured_delay_ns;
};

class ImpairmentEngine {
 public:
  ImpairmentEngine(const ImpairmentConfig& config, const std::string& self_name);
  ~ImpairmentEngine();

  /// The chaining transport's send: decides per destination and sends now or later.
  bool send(eprosima::fastrtps::rtps::SenderResource* low, const uint8_t* data, uint32_t size,
            eprosima::fastdds::rtps::LocatorsIterator* begin, eprosima::fastdds::rtps::LocatorsIterator* end,
            const std::chrono::steady_clock::time_point& timeout);

  /// Messages that took the fast path of an all-transparent configuration.
  uint64_t passed_through() const { return passed_through_.load(std::memory_order_relaxed); }

  /// Learns where peers listen (participant discovery).
  PeerDirectory& peers() { return peers_; }

  /// Stops delaying: pending messages are dropped, later ones pass through unimpaired.
  /// Called before the participant (and its sender resources) is deleted.
  void shutdown();

  std::vector<LinkReport> reports() const;

  /// Copies up to `capacity` links' names (pointers into the engine, stable) and statistics
  /// into `out`; returns how many. No allocation: for status publication from the loop.
  struct Snapshot {
    const std::string* to;
    const std::string* profile;
    LinkStats stats;
  };
  size_t snapshot(Snapshot* out, size_t capacity) const;
  const DelayLine& delay_line() const { return delay_line_; }
  uint64_t seed() const { return seed_; }

 private:
  struct Link {
    std::string to;
    mutable std::mutex mutex;
    LinkModel model;
    Link(std::string peer, const LinkProfile& profile, uint64_t seed, int64_t start_ns)
        : to(std::move(peer)), model(profile, seed, start_ns) {}
  };
  Link* link_for(const eprosima::fastrtps::rtps::Locator_t& destination);

  std::string self_;
  uint64_t seed_;
  bool exclude_discovery_;
  std::vector<std::unique_ptr<Link>> links_;  // by peer index (PeerDirectory)
  Link* any_peer_ = nullptr;
  PeerDirectory peers_;
  DelayLine delay_line_;
  std::atomic<bool> active_{true};
  // every link configured to do nothing: forward whole messages, no per-destination decisions
  bool all_transparent_ = true;
  std::atomic<uint64_t> passed_through_{0};
};

}  // namespace teleop::transport::impairment
