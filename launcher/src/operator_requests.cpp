#include "teleop/launcher/operator_requests.h"

#include <algorithm>
#include <chrono>
#include <set>
#include <string>
#include <thread>

#include "teleop/common/clock.h"
#include "teleop/common/config.h"
#include "teleop/runtime/node_release.h"
#include "teleop/transport/participant.h"
#include "teleop/transport/participant_config.h"
#include "teleop/transport/publication.h"

namespace teleop::launcher {
namespace {

// the readers found once the first one matched: the nodes that are there announce themselves
// within this (discovery's initial announcements), one request reaches them all
constexpr std::chrono::milliseconds kMoreReadersWithin{300};
// statuses come at 10 Hz once matched: within this every node on the domain has said its name,
// also on a loaded host
constexpr int64_t kNodesHeardWithinNs = 1'500'000'000;

// waits for one reader (the followers take resets), sends, waits for the acknowledgments
int send_once(transport::Publication<msg::ResetRequest>& request, int64_t deadline_ns) {
  while (request.matched() == 0) {
    if (monotonic_now_ns() > deadline_ns) return 0;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  std::this_thread::sleep_for(kMoreReadersWithin);
  if (!request.publish()) return 0;
  return request.wait_for_acknowledgments(std::max<int64_t>(deadline_ns - monotonic_now_ns(), 0)) ? request.matched() : 0;
}

// sends at the first reader's match, at once (a stop must not wait for discovery), and again to
// each reader matched later, until a reader of every node of this release heard on the domain has
// it (each node has one reader of the stop chain; a repeat changes nothing); then waits for the
// acknowledgments
int send_to_every_node(transport::Participant& participant, transport::Publication<msg::EmergencyStop>& request,
                       int64_t deadline_ns) {
  transport::Reader<msg::NodeStatus> statuses = participant.make_reader(transport::topics::kNodeStatus);
  msg::NodeStatus status;
  std::set<std::string> nodes;
  const int64_t heard_by_ns = monotonic_now_ns() + kNodesHeardWithinNs;
  int32_t sent_to = 0;
  for (;;) {
    while (statuses.take_next(status)) {
      if (runtime::speaks_this_release(status)) nodes.insert(status.header().source().c_str());
    }
    const int32_t matched = request.matched();
    if (matched > sent_to) {
      if (!request.publish()) return 0;
      sent_to = matched;
    }
    const int64_t now_ns = monotonic_now_ns();
    if (now_ns > deadline_ns || (now_ns > heard_by_ns && sent_to >= static_cast<int32_t>(nodes.size()) && sent_to > 0)) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  if (sent_to == 0) return 0;
  return request.wait_for_acknowledgments(std::max<int64_t>(deadline_ns - monotonic_now_ns(), 0)) ? request.matched() : 0;
}

template <typename Sample>
struct Request {
  transport::Participant participant;
  transport::Publication<Sample> publication;
  int64_t deadline_ns;
  Request(const BusRequestOptions& options, const transport::TopicSpec<Sample>& topic, const char* tool)
      : participant(transport::tool_participant_config(options.config_path, options.domain_id, tool)),
        publication(participant, topic, tool),
        deadline_ns(monotonic_now_ns() + static_cast<int64_t>(options.timeout_s * 1e9)) {}
};

}  // namespace

int send_reset(const ResetOptions& options) {
  Request<msg::ResetRequest> r(options, transport::topics::kResetRequest, "teleop_reset");
  r.publication.sample().target(options.target);
  return send_once(r.publication, r.deadline_ns);
}

int send_emergency_stop(const BusRequestOptions& options, bool engaged, const std::string& origin) {
  Request<msg::EmergencyStop> r(options, transport::topics::kEmergencyStop, engaged ? "teleop_estop" : "teleop_enable");
  msg::EmergencyStop& s = r.publication.sample();
  s.engaged(engaged);
  s.target(options.target);
  s.origin(origin);
  return send_to_every_node(r.participant, r.publication, r.deadline_ns);
}

}  // namespace teleop::launcher
