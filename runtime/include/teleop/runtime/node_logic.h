#pragma once
// What distinguishes the leader, the follower and the twin: their per-cycle work.

#include <cstdint>
#include <string>
#include <vector>

#include <teleop/msg/status.h>

#include "teleop/common/rate_pacer.h"
#include "teleop/runtime/node_report.h"

namespace teleop::runtime {

/// The control logic of a node, run by NodeRunner once per cycle.
class NodeLogic {
 public:
  virtual ~NodeLogic() = default;

  /// One control cycle. Real-time: no allocation, no blocking, no exceptions, no logging.
  virtual void cycle(const CycleTick& tick) = 0;
  /// The node's state-machine state, published in NodeStatus. Real-time safe.
  virtual msg::NodeState state() const = 0;
  /// Active fault codes (msg::FAULT_*), appended to `faults`. Real-time safe once `faults` has capacity.
  virtual void active_faults(std::vector<uint32_t>& faults) const = 0;
  /// Adds what only this node knows to its NodeStatus (TDPA energy, the CAN bus state); the
  /// runner has filled the rest. Real-time safe: no allocation.
  virtual void fill_status(msg::NodeStatus& status) const { (void)status; }
  /// An emergency stop engaged (true), or ended by a deliberate enable (false): told before the
  /// work of the first cycle after it arrived (docs/stop_chain.md). A node that moves something
  /// stops it and keeps it stopped until told false (the follower holds its robot and follows no
  /// command, the leader freezes its command and renders no force); meanwhile the runner reports the
  /// node in STATE_FAULT with FAULT_EMERGENCY_STOP. Real-time safe.
  virtual void emergency_stop(bool engaged) { (void)engaged; }
  /// An enable arrived while no emergency stop is engaged: a node whose holds wait for a deliberate
  /// enable (the follower with `after_hold: enable`) leaves the one it is in. True when it ended
  /// a hold. Real-time safe.
  virtual bool enable_requested() { return false; }
  /// Adds the node's topics and counters to the final report. Called once after the loop.
  virtual void fill_report(NodeReport& report) const = 0;

  /// A time the loop's deadlines should fall on, modulo the period (the follower of a robot that
  /// keeps its own cycle: just after the robot's state arrives), or 0: the loop keeps its own grid.
  /// Asked after each cycle. Real-time safe.
  virtual int64_t pacing_phase_ns() const { return 0; }

  /// The names of the node's time-trace columns (`--trace FILE`), appended to `columns`. Called
  /// once before the loop; none (the default): the node writes no trace.
  virtual void trace_columns(std::vector<std::string>& columns) const { (void)columns; }
  /// This cycle's trace values, one per column in trace_columns() order, written into `row`
  /// (preset to NaN). Called after each cycle() when tracing. Real-time: no allocation, no blocking.
  virtual void trace_row(double* row) const { (void)row; }
};

}  // namespace teleop::runtime
