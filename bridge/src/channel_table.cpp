#include "channel_table.h"

namespace teleop::bridge {

Channel ChannelTable::add(Channel channel) {
  std::lock_guard lock(mutex_);
  channel.id = static_cast<uint32_t>(channels_.size() + 1);
  channels_.push_back(std::move(channel));
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
