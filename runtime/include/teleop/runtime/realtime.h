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

/// The node's other threads (Fast DDS's receive, event and discovery threads, the node's log and
/// trace writers) as the scheduler sees them.
struct ThreadCensus {
  int threads = 0;    ///< besides the calling (loop) thread
  int realtime = 0;   ///< of them, with a real-time policy (SCHED_FIFO or SCHED_RR)
  int demoted = 0;    ///< of those, put back to SCHED_OTHER by keep_other_threads_below()
};

/// Fast DDS 2.9 has no thread-settings API: its threads are created with the participant and
/// inherit the creating thread's scheduling. The loop raises only itself, after they exist, so
/// they stay at SCHED_OTHER, below it; this checks that for every thread of the process (from
/// /proc/self/task) and puts any other real-time thread back to SCHED_OTHER, so that nothing on
/// the bus (discovery storms, slow readers) can run before the loop. Not for the loop itself.
ThreadCensus keep_other_threads_below();

}  // namespace teleop::runtime
