#include "peer_versions.h"

#include <functional>
#include <string_view>

#include "teleop/common/clock.h"
#include "teleop/runtime/node_release.h"

namespace teleop::runtime {

PeerVersions::PeerVersions(transport::Participant& participant, std::string self_name)
    : self_(std::move(self_name)),
      statuses_(participant.make_reader(transport::topics::kNodeStatus,
                                        gate_.guard(std::function<void(const msg::NodeStatus&)>(
                                            [this](const msg::NodeStatus& s) { judge(s); })))) {}

void PeerVersions::judge(const msg::NodeStatus& status) {
  const std::string_view source(status.header().source().c_str());
  if (!says_its_release(status) || speaks_this_release(status) || source == self_) return;
  {
    const std::lock_guard<std::mutex> lock(words_);
    last_.peer.assign(source);
    last_.peer_protocol = status.protocol_version();
    last_.peer_messages.assign(status.message_version().c_str());
    last_.peer_software.assign(status.software_version().c_str());
  }
  mismatch_seen_ns_.store(monotonic_now_ns(), std::memory_order_release);
}

bool PeerVersions::last_mismatch(VersionMismatch& out) const {
  const std::unique_lock<std::mutex> lock(words_, std::try_to_lock);
  if (!lock.owns_lock()) return false;
  out = last_;
  return true;
}

}  // namespace teleop::runtime
