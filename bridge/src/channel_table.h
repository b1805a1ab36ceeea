#pragma once
// The channels the bridge advertises: one per teleop topic it listens to, numbered from 1 in the
// order discovery found them. Added on the bridge's main thread, read on the server's.

#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

#include "foxglove_protocol.h"

namespace teleop::bridge {

class ChannelTable {
 public:
  /// Adds `channel` under the next id and returns it with that id.
  Channel add(Channel channel);
  std::vector<Channel> all() const;
  bool contains(uint32_t id) const;

 private:
  mutable std::mutex mutex_;
  std::vector<Channel> channels_;
};

}  // namespace teleop::bridge
