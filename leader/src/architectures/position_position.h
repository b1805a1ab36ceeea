#pragma once
// position_position at the leader: the mapped joints go out as joint impedance commands (the
// leader's K and D), and the operator feels the spring-damper the follower's impedance exerts,
// K (q_f - q_cmd) + D (dq_f - dq_cmd), from the follower's measured state.

#include "leader_architecture.h"

namespace teleop::leader {

class PositionPositionLeader : public LeaderArchitecture {
 public:
  explicit PositionPositionLeader(const LeaderSetup& setup);

  bool cartesian() const override { return false; }
  WriterId authority_writer() const override { return command_.writer_id(); }
  const std::string& authority_topic() const override { return command_.topic_name(); }
  void send(const MappedDevice& device) override;
  bool feedback(const MappedDevice& device, int64_t now_ns, JointVector& feedback, uint64_t& rejected) override;
  void report_command(runtime::NodeReport& report) const override { report.add(command_); }

 private:
  const LeaderConfig& config_;
  const transport::Subscription<msg::JointState>& follower_state_;
  transport::Publication<msg::JointCommand> command_;
};

}  // namespace teleop::leader
