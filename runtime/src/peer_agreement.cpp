#include "peer_agreement.h"

#include <functional>
#include <string_view>

#include "teleop/common/clock.h"
#include "teleop/runtime/node_release.h"

namespace teleop::runtime {

PeerAgreement::PeerAgreement(transport::Participant& participant, std::string self_name, std::string architecture)
    : self_(std::move(self_name)),
      architecture_(std::move(architecture)),
      statuses_(participant.make_reader(transport::topics::kNodeStatus,
                                        gate_.guard(std::function<void(const msg::NodeStatus&)>(
                                            [this](const msg::NodeStatus& s) { judge(s); })))) {}

void PeerAgreement::judge(const msg::NodeStatus& status) {
  const std::string_view source(status.header().source().c_str());
  if (source == self_) return;
  judged_.fetch_add(1, std::memory_order_acq_rel);
  if (!says_its_release(status)) return;
  if (!speaks_this_release(status)) {
    // what follows the versions may mean anything in another release: nothing more is judged
    record(Disagreement::kVersion, status);
    return;
  }
  const std::string_view theirs(status.architecture().c_str());
  if (!architecture_.empty() && !theirs.empty() && theirs != architecture_) record(Disagreement::kArchitecture, status);
}

void PeerAgreement::record(Disagreement what, const msg::NodeStatus& status) {
  Slot& slot = slots_[index(what)];
  {
    const std::lock_guard<std::mutex> lock(words_);
    slot.last.peer.assign(status.header().source().c_str());
    slot.last.peer_protocol = status.protocol_version();
    slot.last.peer_messages.assign(status.message_version().c_str());
    slot.last.peer_software.assign(status.software_version().c_str());
    slot.last.peer_architecture.assign(status.architecture().c_str());
  }
  slot.seen_ns.store(monotonic_now_ns(), std::memory_order_release);
}

bool PeerAgreement::last_mismatch(Disagreement what, PeerMismatch& out) const {
  const std::unique_lock<std::mutex> lock(words_, std::try_to_lock);
  if (!lock.owns_lock()) return false;
  out = slots_[index(what)].last;
  return true;
}

}  // namespace teleop::runtime
