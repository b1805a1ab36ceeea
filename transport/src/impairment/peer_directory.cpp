#include "teleop/transport/impairment/peer_directory.h"

#include <algorithm>

namespace teleop::transport::impairment {

void PeerDirectory::set_peer_names(const std::vector<std::string>& names) {
  std::lock_guard lock(mutex_);
  names_ = names;
  entries_.reserve(64);
}

void PeerDirectory::add(const std::string& peer, const std::vector<eprosima::fastrtps::rtps::Locator_t>& locators) {
  std::lock_guard lock(mutex_);
  const auto it = std::find(names_.begin(), names_.end(), peer);
  if (it == names_.end()) return;
  const int index = static_cast<int>(it - names_.begin());
  std::erase_if(entries_, [&](const Entry& e) { return e.peer == index; });
  for (const auto& loc : locators) entries_.push_back({loc, index});
}

void PeerDirectory::remove(const std::string& peer) {
  std::lock_guard lock(mutex_);
  const auto it = std::find(names_.begin(), names_.end(), peer);
  if (it == names_.end()) return;
  const int index = static_cast<int>(it - names_.begin());
  std::erase_if(entries_, [&](const Entry& e) { return e.peer == index; });
}

int PeerDirectory::lookup(const eprosima::fastrtps::rtps::Locator_t& locator) const {
  std::lock_guard lock(mutex_);
  for (const auto& e : entries_) {
    if (e.locator == locator) return e.peer;
  }
  return -1;
}

}  // namespace teleop::transport::impairment
