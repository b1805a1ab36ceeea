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
  /// Adds a channel and returns it with its id.
  Channel add(const std::string& topic, const std::string& schema_name, const std::string& schema);
  std::vector<Channel> all() const;
  bool contains(uint32_t id) const;

 private:
  mutable std::mutex mutex_;
  std::vector<Channel> channels_;
};

}  // namespace teleop::bridge
