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
  /// SCHED_FIFO priority of the middleware's threads (receive, events, discovery), below the
  /// loop's; 0: SCHED_OTHER. Real-time, so that no ordinary process on the host (a storm of
  /// readers, a build) starves the reception of commands or holds a lock the loop waits for.
  int dds_priority = 70;
};

/// Applies the settings to the calling thread (call from the loop thread, after the DDS threads
/// exist, so that only the loop gets the priority). Returns an empty string on success, or what
/// failed. Setup time only.
std::string apply_realtime(const RealtimeConfig& config);

/// The node's other threads as the scheduler sees them after place_other_threads().
struct ThreadCensus {
  int middleware = 0;  ///< Fast DDS's threads (unnamed), now at the middleware's priority
  int own = 0;         ///< the node's helper threads (named "teleop-..."), at SCHED_OTHER
  int refused = 0;     ///< threads the kernel refused to move
};

/// Fast DDS 2.9 has no thread-settings API: its threads are created with the participant and
/// inherit the creating thread's scheduling, and it does not name them. The loop raises only
/// itself, after they exist; this then puts every other thread of the process (/proc/self/task)
/// in its place: the node's own helpers (logs, traces; named "teleop-...") at SCHED_OTHER, the
/// rest (Fast DDS's) at SCHED_FIFO `config.dds_priority` (SCHED_OTHER for 0), below the loop.
/// Call from the loop thread after apply_realtime(). Setup time.
ThreadCensus place_other_threads(const RealtimeConfig& config);

/// Names the calling thread "teleop-<what>" (at most 15 characters), which marks it as one of
/// the node's own helpers for place_other_threads().
void name_own_thread(const char* what);

}  // namespace teleop::runtime
