#include "teleop/launcher/reset_request.h"

#include <chrono>
#include <thread>

#include "teleop/common/clock.h"
#include "teleop/common/config.h"
#include "teleop/transport/participant.h"
#include "teleop/transport/participant_config.h"
#include "teleop/transport/publication.h"

namespace teleop::launcher {

bool send_reset(const ResetOptions& options) {
  transport::Participant participant(
      transport::tool_participant_config(options.config_path, options.domain_id, "teleop_reset"));
  transport::Publication<msg::ResetRequest> request(participant, transport::topics::kResetRequest, "teleop_reset");
  request.sample().target(options.target);
  const int64_t deadline_ns = monotonic_now_ns() + static_cast<int64_t>(options.timeout_s * 1e9);
  while (request.matched() == 0) {
    if (monotonic_now_ns() > deadline_ns) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  // reliable and volatile: the readers matched now get it, and acknowledge it
  if (!request.publish()) return false;
  return request.wait_for_acknowledgments(std::max<int64_t>(deadline_ns - monotonic_now_ns(), 0));
}

}  // namespace teleop::launcher
