#pragma once
// One node for a multi-arm robot: the logic of each arm (a LeaderNode or FollowerNode on its own
// arm topics, transport/arm_topic.h) runs in a fixed order every cycle, then an optional common
// step. Both arms of a two-arm robot live in one process because they share a world: the
// follower's arms hold the same box, so they must be one simulation that advances once both have
// written their torques (the common step), and the operator's two hands move together.

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "teleop/runtime/node_logic.h"

namespace teleop::runtime {

class ArmGroup final : public NodeLogic {
 public:
  struct Arm {
    /// "" for a member that is no arm (an observer of the shared scene): its columns and
    /// counters keep their own names.
    std::string name;
    std::unique_ptr<NodeLogic> logic;
  };

  /// `after_arms` runs each cycle after every arm's cycle (it must be real-time safe).
  explicit ArmGroup(std::vector<Arm> arms, std::function<void()> after_arms = {});

  void cycle(const CycleTick& tick) override;
  /// The worst state of any arm: fault, then safe hold, starting, stopping, running.
  msg::NodeState state() const override;
  void active_faults(std::vector<uint32_t>& faults) const override;
  /// Every arm stops (and is enabled) together.
  void emergency_stop(bool engaged) override;
  bool enable_requested() override;
  /// Every arm's topics; its counters as "<arm>.<counter>" (unnamed members: as they are).
  void fill_report(NodeReport& report) const override;
  /// Every arm's columns as "<arm>_<column>" (unnamed members: as they are).
  void trace_columns(std::vector<std::string>& columns) const override;
  void trace_row(double* row) const override;

  const NodeLogic& arm(size_t i) const { return *arms_[i].logic; }
  size_t arms() const { return arms_.size(); }

 private:
  std::vector<Arm> arms_;
  std::function<void()> after_arms_;
  std::vector<size_t> trace_widths_;
};

}  // namespace teleop::runtime
