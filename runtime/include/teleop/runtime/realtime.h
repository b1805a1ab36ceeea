#pragma once
// Real-time setup of the control thread: locked memory and a SCHED_FIFO priority.

#include <string>

namespace teleop::runtime {

enum class RealtimeMode {
  kOff,       ///< normal scheduling (default: works everywhere, e.g. CI and laptops)
  kOptional,  ///< try; warn and continue without when the system does not allow it
  kRequired,  ///< fail at start when the system does not allow it (a robot on an RT host)
};

struct RealtimeConfig {
  RealtimeMode mode = RealtimeMode::kOff;
  int priority = 80;
};

/// Applies the settings to the calling thread (call from the loop thread, after the DDS threads
/// exist, so that only the loop gets the priority). Returns an empty string on success, or what
/// failed. Setup time only.
std::string apply_realtime(const RealtimeConfig& config);

}  // namespace teleop::runtime
