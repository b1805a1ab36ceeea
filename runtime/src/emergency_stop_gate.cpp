#include "emergency_stop_gate.h"

#include <algorithm>

#include "teleop/common/clock.h"
#include "teleop/transport/topics.h"

namespace teleop::runtime {

EmergencyStopGate::EmergencyStopGate(std::unique_ptr<NodeLogic> logic, transport::Participant& participant,
                                     std::string node_name, std::string architecture)
    : logic_(std::move(logic)),
      name_(std::move(node_name)),
      requests_(participant.make_reader(transport::topics::kEmergencyStop)),
      events_(&participant.events()),
      peers_(participant, name_, std::move(architecture)) {}

bool EmergencyStopGate::addressed_to_us(const msg::EmergencyStop& request) const {
  const std::string_view target = request.target().c_str();
  return target.empty() || target == name_;
}

void EmergencyStopGate::log_change(const msg::EmergencyStop& request, int64_t now_ns, bool hold) {
  NodeEvent e;
  e.kind = NodeEvent::Kind::kEmergencyStop;
  e.mono_ns = now_ns;
  e.code = engaged_ ? 1 : hold ? 2 : 0;
  e.who.assign(request.header().source().c_str());
  e.topic.assign(request.origin().c_str());
  events_->push(e);
}

void EmergencyStopGate::cycle(const CycleTick& tick) {
  watch_peers(tick.now_ns);
  int64_t reception_ns = 0;
  WriterId writer;
  while (requests_.take_next(request_, reception_ns, writer)) {
    if (!addressed_to_us(request_)) continue;
    // the first cycle after the arrival acts on it: its start is the reaction's end
    reaction_max_ns_ = std::max(reaction_max_ns_, system_now_ns() - reception_ns);
    if (request_.engaged() == engaged_) {
      // a repeat changes nothing; an enable while not stopped may end a hold that waits for one
      if (!engaged_ && !any_mismatch() && logic_->enable_requested()) {
        ++hold_enables_;
        log_change(request_, tick.now_ns, /*hold=*/true);
      }
      continue;
    }
    // nothing resumes a node while a peer that disagrees talks on the domain
    if (!request_.engaged() && any_mismatch()) {
      ++enables_refused_;
      continue;
    }
    emergency_stop(request_.engaged());
    log_change(request_, tick.now_ns, /*hold=*/false);
  }
  logic_->cycle(tick);
}

void EmergencyStopGate::watch_peers(int64_t now_ns) {
  watch_peer(Disagreement::kVersion, now_ns);
  watch_peer(Disagreement::kArchitecture, now_ns);
}

void EmergencyStopGate::watch_peer(Disagreement what, int64_t now_ns) {
  const auto i = static_cast<size_t>(what);
  const bool mismatched = peers_.mismatched(what, now_ns);
  if (mismatched == mismatched_[i]) return;
  mismatched_[i] = mismatched;
  NodeEvent e;
  e.mono_ns = now_ns;
  e.code = mismatched ? 1 : 0;
  PeerMismatch words;
  const bool named = peers_.last_mismatch(what, words);
  if (named) e.who = words.peer;
  if (what == Disagreement::kVersion) {
    e.kind = NodeEvent::Kind::kVersionMismatch;
    if (named) {
      e.count = words.peer_protocol;
      e.topic.assign(words.peer_messages.view());
      e.detail = words.peer_software;
    }
  } else {
    e.kind = NodeEvent::Kind::kArchitectureMismatch;
    e.topic.assign(peers_.architecture());
    if (named) e.detail = words.peer_architecture;
  }
  events_->push(e);
  if (!mismatched || engaged_) return;
  ++mismatch_stops_[i];
  engaged_ = true;
  logic_->emergency_stop(true);
}

void EmergencyStopGate::emergency_stop(bool engaged) {
  engaged_ = engaged;
  ++(engaged ? stops_ : enables_);
  logic_->emergency_stop(engaged);
}

void EmergencyStopGate::active_faults(std::vector<uint32_t>& faults) const {
  logic_->active_faults(faults);
  // the follower names the cause of its hold itself
  if (engaged_ && std::find(faults.begin(), faults.end(), msg::FAULT_EMERGENCY_STOP) == faults.end()) {
    faults.push_back(msg::FAULT_EMERGENCY_STOP);
  }
  if (mismatched_[static_cast<size_t>(Disagreement::kVersion)]) faults.push_back(msg::FAULT_VERSION_MISMATCH);
  if (mismatched_[static_cast<size_t>(Disagreement::kArchitecture)]) faults.push_back(msg::FAULT_ARCHITECTURE_MISMATCH);
}

void EmergencyStopGate::fill_report(NodeReport& report) const {
  logic_->fill_report(report);
  report.counters.emplace_back("emergency_stops", static_cast<double>(stops_));
  report.counters.emplace_back("emergency_stop_enables", static_cast<double>(enables_));
  report.counters.emplace_back("hold_enables", static_cast<double>(hold_enables_));
  report.counters.emplace_back("emergency_stop_engaged", engaged_ ? 1.0 : 0.0);
  report.counters.emplace_back("emergency_stop_reaction_max_ms", static_cast<double>(reaction_max_ns_) * 1e-6);
  report.counters.emplace_back("version_mismatch_stops", static_cast<double>(mismatch_stops_[0]));
  report.counters.emplace_back("architecture_mismatch_stops", static_cast<double>(mismatch_stops_[1]));
  report.counters.emplace_back("enables_refused", static_cast<double>(enables_refused_));
}

void EmergencyStopGate::trace_columns(std::vector<std::string>& columns) const {
  const size_t before = columns.size();
  logic_->trace_columns(columns);
  logic_columns_ = columns.size() - before;
  // a node without a trace of its own keeps writing none
  if (logic_columns_ > 0) columns.emplace_back("emergency_stop");
}

void EmergencyStopGate::trace_row(double* row) const {
  logic_->trace_row(row);
  row[logic_columns_] = engaged_ ? 1.0 : 0.0;
}

}  // namespace teleop::runtime
