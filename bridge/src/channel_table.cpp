#include "channel_table.h"

namespace teleop::bridge {

Channel ChannelTable::add(const std::string& topic, const std::string& schema_name, const std::string& schema) {
  std::lock_guard lock(mutex_);
  channels_.push_back({static_cast<uint32_t>(channels_.size() + 1), topic, schema_name, schema});
  return channels_.back();
}

std::vector<Channel> ChannelTable::all() const {
  std::lock_guard lock(mutex_);
  return channels_;
}

bool ChannelTable::contains(uint32_t id) const {
  std::lock_guard lock(mutex_);
  return id >= 1 && id <= channels_.size();
}

}  // namespace teleop::bridge
