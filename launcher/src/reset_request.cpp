#include "teleop/launcher/reset_request.h"

#include <chrono>
#include <thread>

#include "teleop/common/clock.h"
#include "teleop/common/config.h"
#include "teleop/transport/participant.h"
#include "teleop/transport/participant_config.h"
#include "teleop/transport/publication.h"

namespace teleop::launcher {
namespace {

// the readers found once the first one matched: the nodes that are there announce themselves
// within this (discovery's initial announcements), one request reaches them all
constexpr std::chrono::milliseconds kMoreReadersWithin{300};

template <typename Sample, typename Fill>
int send_acknowledged(const BusRequestOptions& options, const transport::TopicSpec<Sample>& topic, const char* tool,
                      Fill fill) {
  transport::Participant participant(transport::tool_participant_config(options.config_path, options.domain_id, tool));
  transport::Publication<Sample> request(participant, topic, tool);
  fill(request.sample());
  const int64_t deadline_ns = monotonic_now_ns() + static_cast<int64_t>(options.timeout_s * 1e9);
  while (request.matched() == 0) {
    if (monotonic_now_ns() > deadline_ns) return 0;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  std::this_thread::sleep_for(kMoreReadersWithin);
  // reliable and volatile: the readers matched now get it, and acknowledge it
  if (!request.publish()) return 0;
  if (!request.wait_for_acknowledgments(std::max<int64_t>(deadline_ns - monotonic_now_ns(), 0))) return 0;
  return request.matched();
}

}  // namespace

int send_reset(const ResetOptions& options) {
  return send_acknowledged(options, transport::topics::kResetRequest, "teleop_reset",
                           [&](msg::ResetRequest& r) { r.target(options.target); });
}

int send_emergency_stop(const BusRequestOptions& options, bool engaged, const std::string& origin) {
  return send_acknowledged(options, transport::topics::kEmergencyStop, engaged ? "teleop_estop" : "teleop_enable",
                           [&](msg::EmergencyStop& s) {
                             s.engaged(engaged);
                             s.target(options.target);
                             s.origin(origin);
                           });
}

}  // namespace teleop::launcher
