#include "flow_watch.h"

#include <spdlog/spdlog.h>

#include <chrono>

#include "teleop/common/clock.h"
#include "teleop/runtime/realtime.h"

namespace teleop::runtime {

FlowWaitTracker::FlowWaitTracker(size_t flows, int64_t grace_ns, int64_t start_ns)
    : flows_(flows, Flow{false, start_ns}), grace_ns_(grace_ns) {}

void FlowWaitTracker::update(int64_t now_ns, const std::vector<int32_t>& writers, std::vector<FlowEvent>& events) {
  for (size_t i = 0; i < flows_.size() && i < writers.size(); ++i) {
    Flow& f = flows_[i];
    if (writers[i] > 0) {
      if (f.reported) events.push_back({FlowEvent::Kind::kAppeared, i, (now_ns - f.without_since_ns) * 1e-9});
      f = Flow{true, 0};
      continue;
    }
    if (f.has_writer) f = Flow{false, now_ns};  // its writer went away
    if (!f.reported && now_ns - f.without_since_ns >= grace_ns_) {
      events.push_back({FlowEvent::Kind::kWaiting, i, (now_ns - f.without_since_ns) * 1e-9});
      f.reported = true;
    }
  }
}

FlowWatch::FlowWatch(const transport::Participant& participant, std::string node_name, int domain_id, int64_t grace_ns)
    : flows_(participant.reader_flows()),
      node_name_(std::move(node_name)),
      domain_id_(domain_id),
      tracker_(flows_.size(), grace_ns, monotonic_now_ns()),
      thread_([this] { run(); }) {}

FlowWatch::~FlowWatch() {
  stop_.request();
  thread_.join();
}

void FlowWatch::run() {
  name_own_thread("flows");
  std::vector<int32_t> writers(flows_.size());
  std::vector<FlowEvent> events;
  do {
    for (size_t i = 0; i < flows_.size(); ++i) {
      const transport::EndpointStatus& s = *flows_[i].status;
      // a flow the node does not need counts as served: nothing to wait for
      writers[i] = s.awaited.load(std::memory_order_relaxed) ? s.matched.load(std::memory_order_relaxed) : 1;
    }
    events.clear();
    tracker_.update(monotonic_now_ns(), writers, events);
    for (const FlowEvent& e : events) log(e);
  } while (!stop_.wait_for(std::chrono::milliseconds(100)));
}

void FlowWatch::log(const FlowEvent& event) const {
  const std::string& topic = flows_[event.flow].topic;
  if (event.kind == FlowEvent::Kind::kWaiting) {
    spdlog::warn("{}: waiting for a writer on {}, domain {} (none for {:.1f} s)", node_name_, topic, domain_id_,
                 event.without_writer_s);
  } else {
    spdlog::info("{}: a writer on {} appeared after {:.1f} s without", node_name_, topic, event.without_writer_s);
  }
}

}  // namespace teleop::runtime
