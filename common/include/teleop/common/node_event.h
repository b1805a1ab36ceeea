#pragma once
// What happened in a node, as the control loop saw it: a state change, a writer followed or
// refused, a stall. The loop records events without allocating (fixed-size text, a lock-free
// queue); a thread of the node formats and logs them (runtime/node_event_log.h), so that every
// such change is a log line at the moment it happens, not a line in the report at the end.

#include <cstdint>

#include "teleop/common/fixed_text.h"
#include "teleop/common/spsc_queue.h"

namespace teleop {

struct NodeEvent {
  enum class Kind : uint8_t {
    kState,      ///< the node's state changed: `previous` -> `code`, `faults` active now
    kFollowing,  ///< a flow follows a writer now (`who`, its session `count`)
    kRefused,    ///< a flow refused a writer's sample for the first time for this cause (`code`, `detail`)
    kStall,      ///< the loop stalled: `count` deadlines skipped over `value` seconds
    kAuthority,  ///< whether the node's commands are in force changed: why not (`code`), at `who`, `detail`
    kEmergencyStop,  ///< an emergency stop engaged (`code` 1) or was ended by an enable (0), or an enable ended a hold waiting for one (2); sent by `who` from `topic`
    kVersionMismatch,  ///< a peer `who` of protocol `count`, messages `topic`, software `detail` is heard (`code` 1) or gone (0)
    kArchitectureMismatch,  ///< a peer `who` playing architecture `detail` is heard (`code` 1) or gone (0); ours is `topic`
    kClockOffset,    ///< `who`'s samples on `topic` arrive `value` seconds after their stamps at best (clocks apart)
  };
  Kind kind = Kind::kState;
  int64_t mono_ns = 0;
  int32_t code = 0;
  int32_t previous = 0;
  /// Bit k set: fault code k is active (kState).
  uint32_t faults = 0;
  uint64_t count = 0;
  double value = 0.0;
  FixedText<64> topic;
  FixedText<32> who;
  FixedText<32> detail;
};

/// The loop's events on their way to the log.
using NodeEventQueue = SpscQueue<NodeEvent, 256>;

}  // namespace teleop
