#pragma once
// Which peer (participant name) listens at which locator, learned from discovery, so that a
// message to a locator can be impaired as the link to that peer.


// first: Fast DDS headers need LocatorsIterator declared before Locator
#include <fastdds/rtps/transport/TransportInterface.h>
#include <mutex>
#include <string>
#include <vector>

namespace teleop::transport::impairment {

class PeerDirectory {
 public:
  /// Records (or replaces) the locators a peer announced. Discovery thread.
  void add(const std::string& peer, const std::vector<eprosima::fastrtps::rtps::Locator_t>& locators);
  /// Forgets a peer that left. Discovery thread.
  void remove(const std::string& peer);
  /// Index of the peer listening at `locator` in the list passed to `set_peer_names`, or -1.
  /// Takes a short lock; no allocation.
  int lookup(const eprosima::fastrtps::rtps::Locator_t& locator) const;
  /// The peer names lookups resolve to (in order); others are not tracked.
  void set_peer_names(const std::vector<std::string>& names);

 private:
  struct Entry {
    eprosima::fastrtps::rtps::Locator_t locator;
    int peer;
  };
  mutable std::mutex mutex_;
  std::vector<std::string> names_;
  std::vector<Entry> entries_;
};

}  // namespace teleop::transport::impairment
