#include "teleop/runtime/realtime.h"

#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>

#include <cerrno>
#include <cstring>

namespace teleop::runtime {

std::string apply_realtime(const RealtimeConfig& config) {
  if (config.mode == RealtimeMode::kOff) return {};
  // no page faults in the loop: lock what is mapped now and what will be
  if (mlockall(MCL_CURRENT | MCL_FUTURE) != 0) {
    return std::string("mlockall failed: ") + std::strerror(errno);
  }
  sched_param param{};
  param.sched_priority = config.priority;
  if (const int err = pthread_setschedparam(pthread_self(), SCHED_FIFO, &param); err != 0) {
    return "SCHED_FIFO priority " + std::to_string(config.priority) + " refused: " + std::strerror(err) +
           " (needs CAP_SYS_NICE or an rtprio limit)";
  }
  return {};
}

}  // namespace teleop::runtime
