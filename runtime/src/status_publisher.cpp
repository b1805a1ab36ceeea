#include "status_publisher.h"

#include <algorithm>
#include <cmath>

#include "teleop/common/clock.h"
#include "teleop/common/version.h"

namespace teleop::runtime {

StatusPublisher::StatusPublisher(transport::Participant& participant, const std::string& node_name,
                                 msg::NodeRole role, const std::string& architecture, double loop_rate_hz,
                                 double status_rate_hz)
    : impairment_(participant.impairment()),
      links_(msg::MAX_LINKS),
      publication_(participant, transport::topics::kNodeStatus, node_name),
      cycles_per_status_(std::max<uint64_t>(1, static_cast<uint64_t>(std::llround(loop_rate_hz / status_rate_hz)))) {
  publication_.sample().role(role);
  publication_.sample().protocol_version(kProtocolVersion);
  publication_.sample().message_version(message_version());
  publication_.sample().software_version(software_version().substr(0, 31));
  publication_.sample().architecture(architecture);
  publication_.sample().loop().rate_hz(loop_rate_hz);
  faults_.reserve(msg::MAX_FAULTS);
  publication_.sample().fault_codes().reserve(msg::MAX_FAULTS);
  publication_.sample().links().reserve(msg::MAX_LINKS);
  init_flows(participant);
}

// the flows' names are set once here; each status then only updates numbers (no allocation)
void StatusPublisher::init_flows(const transport::Participant& participant) {
  for (const transport::ReaderFlow& flow : participant.reader_flows()) {
    if (flows_.size() == msg::MAX_FLOWS) break;
    flows_.push_back(flow.status);
    publication_.sample().flows().emplace_back();
    publication_.sample().flows().back().topic(flow.topic);
  }
}

// whom the flow follows, and what it refused (fixed-size names: no allocation)
void StatusPublisher::fill_authority(const transport::FlowAuthority& a, msg::FlowStatus& f) {
  f.following(a.following.text);
  f.following_writer(a.following_writer.text);
  f.in_force(a.in_force);
  f.refused_other_writer(a.refused[msg::REFUSAL_OTHER_WRITER]);
  f.refused_not_accepted(a.refused[msg::REFUSAL_NOT_ACCEPTED]);
  f.refused_sequence_jump(a.refused[msg::REFUSAL_SEQUENCE_JUMP]);
  f.refused_invalid(a.refused[msg::REFUSAL_INVALID]);
  f.refused_source(a.refused_source.text);
  f.refusal(a.refusal);
  f.refusal_detail(a.refusal_detail.text);
}

void StatusPublisher::fill_flows() {
  auto& out = publication_.sample().flows();
  const int64_t now_ns = monotonic_now_ns();
  for (size_t i = 0; i < flows_.size(); ++i) {
    const transport::EndpointStatus& status = *flows_[i];
    msg::FlowStatus& f = out[i];
    f.awaited(status.awaited.load(std::memory_order_relaxed));
    f.writers(status.matched.load(std::memory_order_relaxed));
    f.received(status.received.load(std::memory_order_relaxed));
    f.lost(status.lost.load(std::memory_order_relaxed));
    f.latency_ns(status.latency_ns.load(std::memory_order_relaxed));
    f.clock_offset_ns(status.clock_offset_ns.load(std::memory_order_relaxed));
    const int64_t last = status.last_data_mono_ns.load(std::memory_order_relaxed);
    f.age_ns(last == 0 ? -1 : now_ns - last);
    fill_authority(status.authority, f);
  }
}

void StatusPublisher::fill_links() {
  auto& out = publication_.sample().links();
  out.clear();
  if (impairment_ == nullptr) return;
  const size_t n = impairment_->snapshot(links_.data(), links_.size());
  for (size_t i = 0; i < n; ++i) {
    const auto& snap = links_[i];
    out.emplace_back();  // within the reserved capacity: no allocation
    msg::LinkStatistics& l = out.back();
    l.peer(snap.to->c_str());
    l.profile(snap.profile->c_str());
    l.messages(snap.stats.messages);
    l.delivered(snap.stats.delivered);
    l.lost(snap.stats.lost);
    l.outage(snap.stats.outage);
    l.queue(snap.stats.queue);
    l.duplicated(snap.stats.duplicated);
    l.reordered(snap.stats.reordered);
    l.delay_p50_ns(snap.stats.delay.percentile_ns(0.5));
    l.delay_p99_ns(snap.stats.delay.percentile_ns(0.99));
  }
}

void StatusPublisher::maybe_publish(const CycleTick& tick, const NodeLogic& logic, const PacerStats& loop,
                                    bool changed) {
  if (changed || tick.index % cycles_per_status_ == 0) publish(logic.state(), logic, loop);
}

void StatusPublisher::publish(msg::NodeState state, const NodeLogic& logic, const PacerStats& loop) {
  auto& s = publication_.sample();
  s.state(state);
  faults_.clear();
  logic.active_faults(faults_);
  s.fault_codes().clear();
  for (size_t i = 0; i < faults_.size() && i < msg::MAX_FAULTS; ++i) s.fault_codes().push_back(faults_[i]);
  auto& l = s.loop();
  l.cycles(loop.cycles);
  l.overruns(loop.overruns);
  l.skipped(loop.skipped);
  l.lateness_p50_ns(loop.lateness.percentile_ns(0.50));
  l.lateness_p99_ns(loop.lateness.percentile_ns(0.99));
  l.lateness_max_ns(loop.lateness.max_ns());
  fill_links();
  fill_flows();
  s.tdpa_energy_j(std::nan(""));
  logic.fill_status(s);
  publication_.publish();
}

void StatusPublisher::publish_stopping(const NodeLogic& logic, const PacerStats& loop, int64_t timeout_ns) {
  publish(msg::STATE_STOPPING, logic, loop);
  publication_.wait_for_acknowledgments(timeout_ns);
}

}  // namespace teleop::runtime
