#include "teleop/runtime/command_authority.h"

#include <algorithm>
#include <functional>
#include <string_view>

#include "teleop/common/clock.h"
#include "teleop/runtime/status_names.h"

namespace teleop::runtime {

const char* to_string(CommandRefusal refusal) {
  switch (refusal) {
    case CommandRefusal::kNone: return "in_command";
    case CommandRefusal::kNoTaker: return "no_taker";
    case CommandRefusal::kNotYet: return "not_followed_yet";
    case CommandRefusal::kOtherWriter: return "other_writer_followed";
    case CommandRefusal::kNotAccepted: return "not_accepted";
    case CommandRefusal::kInvalid: return "commands_invalid";
    case CommandRefusal::kHolding: return "robot_holding";
  }
  return "?";
}

CommandAuthority::CommandAuthority(transport::Participant& participant, const WriterId& self,
                                   const std::string& self_name, std::string command_topic)
    : self_(self.hex()),
      command_topic_(std::move(command_topic)),
      events_(&participant.events()),
      statuses_(participant.make_reader(transport::topics::kNodeStatus,
                                        gate_.guard(std::function<void(const msg::NodeStatus&)>(
                                            [this](const msg::NodeStatus& s) { judge(s); })))) {
  self_name_.assign(self_name);
}

namespace {

std::string_view view(const msg::Name& n) { return {n.c_str(), n.size()}; }

}  // namespace

CommandAuthority::Taker& CommandAuthority::slot_for(const msg::Name& name) {
  const auto same = [&](const Taker& t) { return t.name == view(name); };
  if (auto it = std::find_if(takers_.begin(), takers_.end(), same); it != takers_.end()) return *it;
  // a new taker replaces the one heard from longest ago
  Taker& oldest = *std::min_element(takers_.begin(), takers_.end(), [](const Taker& a, const Taker& b) {
    return a.seen_ns.load(std::memory_order_relaxed) < b.seen_ns.load(std::memory_order_relaxed);
  });
  oldest.name.assign(view(name));
  return oldest;
}

void CommandAuthority::judge(const msg::NodeStatus& status) {
  const auto takes = [&](const msg::FlowStatus& f) { return f.awaited() && std::string_view(f.topic()) == command_topic_; };
  const auto flow = std::find_if(status.flows().begin(), status.flows().end(), takes);
  if (flow == status.flows().end()) return;  // this node does not take our commands
  std::lock_guard lock(words_);
  Taker& t = slot_for(status.header().source());
  CommandRefusal refusal = CommandRefusal::kNone;
  t.detail.assign({});
  if (std::string_view(flow->following_writer().c_str()) != std::string_view(self_.data())) {
    const bool refused_us = flow->refusal() == msg::REFUSAL_NOT_ACCEPTED && self_name_ == view(flow->refused_source());
    refusal = refused_us                       ? CommandRefusal::kNotAccepted
              : flow->following().size() == 0 ? CommandRefusal::kNotYet
                                               : CommandRefusal::kOtherWriter;
    t.detail.assign(view(flow->following()));
  } else if (!flow->in_force()) {
    refusal = CommandRefusal::kInvalid;
    t.detail.assign(view(flow->refusal_detail()));
  } else if (status.state() != msg::STATE_RUNNING) {
    refusal = CommandRefusal::kHolding;
    t.detail.assign(status.fault_codes().empty() ? state_name(status.state()) : fault_name(status.fault_codes()[0]));
  }
  t.refusal.store(refusal, std::memory_order_relaxed);
  t.seen_ns.store(monotonic_now_ns(), std::memory_order_release);
}

void CommandAuthority::poll(int64_t now_mono_ns) {
  summarise(now_mono_ns);
  report_change(now_mono_ns);
}

void CommandAuthority::summarise(int64_t now_mono_ns) {
  refusal_ = CommandRefusal::kNoTaker;
  refusing_ = kTakers;
  for (size_t i = 0; i < kTakers; ++i) {
    const int64_t seen = takers_[i].seen_ns.load(std::memory_order_acquire);
    if (seen == 0 || now_mono_ns - seen > kForgetNs) continue;
    if (refusal_ == CommandRefusal::kNoTaker) refusal_ = CommandRefusal::kNone;
    const CommandRefusal r = takers_[i].refusal.load(std::memory_order_relaxed);
    if (r == CommandRefusal::kNone) continue;
    // the first taker that refuses says why
    refusal_ = r;
    refusing_ = i;
    return;
  }
}

// the node's log says when its commands come into force and when not, and why
void CommandAuthority::report_change(int64_t now_mono_ns) {
  if (refusal_ == reported_) return;
  // the words are the reading thread's: never wait for it, tell the change a cycle later instead
  std::unique_lock lock(words_, std::try_to_lock);
  if (!lock.owns_lock()) return;
  taker_.assign({});
  detail_.assign({});
  if (refusing_ < kTakers) {
    taker_ = takers_[refusing_].name;
    detail_ = takers_[refusing_].detail;
  }
  reported_ = refusal_;
  NodeEvent e;
  e.kind = NodeEvent::Kind::kAuthority;
  e.mono_ns = now_mono_ns;
  e.code = static_cast<int32_t>(refusal_);
  e.who = taker_;
  e.detail = detail_;
  events_->push(e);
}

}  // namespace teleop::runtime
