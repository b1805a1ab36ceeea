#pragma once
// Every change in a node is a log line at the moment it happens: the loop records its events
// (common/node_event.h) without allocating or blocking, `StateWatch` adds the node's own state
// and fault changes and its stalls, and `NodeEventLog` formats and logs them from a thread of its
// own, a few milliseconds later, never from the loop.

#include <atomic>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include <teleop/msg/status.h>

#include "teleop/common/node_event.h"
#include "teleop/common/rate_pacer.h"
#include "teleop/runtime/node_logic.h"

namespace teleop::runtime {

/// Records a change of the node's state or faults, and a stall of its loop, as an event.
/// Real-time safe once constructed.
class StateWatch {
 public:
  explicit StateWatch(NodeEventQueue& queue);
  /// After each cycle. True when the state or the faults changed.
  bool after_cycle(const CycleTick& tick, const NodeLogic& logic, const PacerStats& loop);

 private:
  uint32_t fault_mask(const NodeLogic& logic);

  NodeEventQueue& queue_;
  std::vector<uint32_t> faults_;
  bool first_ = true;
  msg::NodeState state_ = msg::STATE_STARTING;
  uint32_t mask_ = 0;
  uint64_t skipped_ = 0;
  int64_t last_deadline_ns_ = 0;
};

/// One event as a log line of node `node` (without the time: spdlog adds it).
std::string format_event(const NodeEvent& event, const std::string& node);

/// Drains the queue every few milliseconds on a thread of its own and logs each event; what is
/// left is logged when it stops.
class NodeEventLog {
 public:
  NodeEventLog(NodeEventQueue& queue, std::string node_name);
  ~NodeEventLog();
  NodeEventLog(const NodeEventLog&) = delete;
  NodeEventLog& operator=(const NodeEventLog&) = delete;

  /// Logs what is queued now (the thread does it too; call once the loop has stopped).
  void drain();

 private:
  void run();

  NodeEventQueue& queue_;
  std::string node_;
  std::mutex consumer_;
  uint64_t dropped_reported_ = 0;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace teleop::runtime
